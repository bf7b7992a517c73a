"""System matrices (Eqs. 13-20, Appendix) of every tip-mass configuration of the simulation cases.

One file per configuration, `results/matrices/<name>.nc`, named by
`hubbeam.matrices.configuration_name` (`mt0`, `mt0p1_l8`, ...), with as many modes as the most
demanding case that uses it (the matrices of fewer modes are its leading blocks).
"""

from snakemake.exceptions import WorkflowError

from hubbeam.matrices import configuration_name
from hubbeam.parameters import TipMass


def matrices_configurations():
    """{name: {"mass", "position", "modes"}} over the tip masses of the configured cases."""
    configurations = {}
    for case in cases():
        settings = case_config(case)
        tip = TipMass(**settings["tip_mass"])
        if tip.mass == 0.0:
            tip = TipMass(mass=0.0, position=config["beam"]["length"])
        entry = configurations.setdefault(
            configuration_name(tip),
            {"mass": tip.mass, "position": tip.position, "modes": settings["modes"]},
        )
        entry["modes"] = max(entry["modes"], settings["modes"])
    return configurations


def matrices_configuration(wildcards):
    """`params:` function: the tip mass and mode count of the job's `{config_name}`."""
    configurations = matrices_configurations()
    if wildcards.config_name not in configurations:
        raise WorkflowError(
            f"results/matrices/{wildcards.config_name}.nc: unknown configuration "
            f"{wildcards.config_name!r}; allowed: {', '.join(sorted(configurations))}"
        )
    return configurations[wildcards.config_name]


def matrices_results():
    """One netCDF file of system matrices per tip-mass configuration."""
    return expand("results/matrices/{config_name}.nc", config_name=sorted(matrices_configurations()))


rule matrices:
    input:
        code=hubbeam_sources("modes.py", "quadrature.py", "matrices.py", "parameters.py"),
    output:
        ensure("results/matrices/{config_name}.nc", non_empty=True),
    params:
        beam=config["beam"],
        configuration=matrices_configuration,
        n_quad=config["numerics"]["quadrature_points"],
    wildcard_constraints:
        config_name=r"mt[0-9a-z_]+",
    log:
        "logs/matrices/{config_name}.log",
    script:
        "../scripts/assemble_matrices.py"
