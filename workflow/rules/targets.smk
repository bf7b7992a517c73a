"""The target rules the families name beside `all` (`snakemake <name>`): `readings` (the claims x
readings matrix alone), `large_sweeps` (the maps too large for every run), `validate` (the
independent validation, which checks its optional dependencies only when it is asked for)."""

for _name, _targets in PLAN.target_rules.items():

    rule:
        name:
            _name
        localrule: True
        input:
            _targets,
