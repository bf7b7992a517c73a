"""Independent validation (docs/validation.md), in ``validation/`` of the results folder: the FOAM
linearisation against published rotating-cantilever frequencies (with the paper's products and
``validation.published``: part of ``all`` and of the reproduction report), the models against the
Exudyn ANCF reference on the validation cases with the mode study and the reference's convergence,
the non-uniform beam checks (Ritz against our finite elements and pyBModes) and their report.
Everything but the published check is built by ``snakemake validate`` only, which needs the
optional dependencies and says so before running anything."""

from __future__ import annotations

import importlib.util

from hubbeam.configuration.schema import CASE_NAME_PATTERN
from hubbeam.pipeline.context import NotPlanned, PlanContext, needs
from hubbeam.pipeline.steps import Step

JOBS, COMPARISONS = "hubbeam.pipeline.jobs.validation", "hubbeam.pipeline.jobs.comparisons"
#: the optional modules ``snakemake validate`` imports: pyBModes always, Exudyn for a ``validation`` section
VALIDATION_MODULES = ("pybmodes", "exudyn")
CAPTIONS = {"published": "../report/rotating_frequencies.rst", "exudyn": "../report/exudyn_comparison.rst",
            "report": "../report/validation_exudyn.rst"}


def nonuniform_checks(ctx: PlanContext) -> dict[str, str]:
    """The tables of the non-uniform checks by name: Ritz against our finite elements always,
    pyBModes for a beam off the hub axis (it needs rA > 0)."""
    checks = ("ritz_fe", "pybmodes") if ctx.settings.beam.rA > 0.0 else ("ritz_fe",)
    return {check: ctx.paths.nonuniform_check(check) for check in checks}


def exudyn_report(ctx: PlanContext) -> dict[str, str]:
    """The Exudyn products the validation report reads, by input name (none without a ``validation`` section)."""
    if ctx.settings.validation is None:
        return {}
    paths = ctx.paths
    return {"comparison": paths.exudyn_comparison("csv"), "figure": paths.exudyn_comparison("png"),
            "mode_study": paths.exudyn_mode_study(), "convergence": paths.exudyn_convergence("csv")}


def published_files(ctx: PlanContext) -> list[str]:
    published = ctx.published_validation()
    return sorted(published.values()) + ([ctx.paths.rotating_frequencies("pdf")] if published else [])


def targets(ctx: PlanContext) -> list[str]:
    """The published-table validation (with the paper's products and ``validation.published``)."""
    return published_files(ctx)


def validation_files(ctx: PlanContext) -> list[str]:
    """What ``snakemake validate`` builds: the published-table validation, the Exudyn comparison
    (with a ``validation`` section), the non-uniform checks and the report of them all."""
    paths, validation = ctx.paths, ctx.settings.validation
    files = published_files(ctx)
    if validation is not None:
        files += [paths.exudyn_comparison("pdf"), paths.exudyn_convergence("nc"), *exudyn_report(ctx).values(),
                  *(paths.exudyn_case(name) for name in validation.cases)]
    return files + list(nonuniform_checks(ctx).values()) + [paths.validation_report("md"),
                                                            paths.validation_report("html")]


def target_rules(ctx: PlanContext) -> dict:
    """``snakemake validate``: its files, once the optional modules it needs are importable (an
    input function, evaluated only when ``validate`` is asked for)."""
    modules = VALIDATION_MODULES if ctx.settings.validation is not None else VALIDATION_MODULES[:1]
    files = validation_files(ctx)

    def validate(wildcards=None) -> list[str]:
        missing = [name for name in modules if importlib.util.find_spec(name) is None]
        if missing:
            raise NotPlanned(
                f"`snakemake validate` needs the optional dependencies {', '.join(modules)}; not installed in this "
                f"environment: {', '.join(missing)}. Install the extra with `pip install -e .[validation]` (from "
                "the repository root), then rerun `snakemake validate`")
        return list(files)

    return {"validate": validate}


def steps(ctx: PlanContext) -> dict[str, Step]:
    paths, settings = ctx.paths, ctx.settings
    validation, beam, numerics = settings.validation, settings.beam, settings.numerics
    names = list(validation.cases) if validation is not None else []
    per_case = [{"vcase": name} for name in names]

    def part(key: str):
        """``validation.<key>``, or, without it, a params function saying the section is needed."""
        value = getattr(validation, key, None) if validation is not None else None
        return needs(f"validation.{key}") if value is None else value

    def validation_case(wildcards):
        """The validation case of a job's ``{vcase}``."""
        if wildcards.vcase not in names:
            raise NotPlanned(f"validation.cases: validation case {wildcards.vcase!r} is not defined; defined: "
                             f"{', '.join(names) or 'none (no validation section)'}")
        return validation.cases[wildcards.vcase]

    def convergence_case(wildcards):
        """The validation case the reference's convergence study runs (``validation.convergence.case``)."""
        if validation is None:
            needs("validation.convergence")(wildcards)
        name = validation.convergence.case
        if name not in names:
            raise NotPlanned(f"validation.convergence.case: validation case {name!r} is not defined; defined: "
                             f"{', '.join(names)}")
        return validation.cases[name]

    cases_or_needed = names or needs("validation.cases")
    return {
        "validate_published": ctx.step(
            f"{COMPARISONS}:validate_published",
            output={"table": paths.published_comparison(), "tip_mass": paths.tip_mass_comparison(),
                    "curves": paths.rotating_eigen(), "pdf": paths.rotating_frequencies("pdf"),
                    "png": paths.rotating_frequencies("png")},
            log=paths.log("validation", "published.log"), input={"style": ctx.style},
            params={"published": part("published"), "n_quad": numerics.quadrature_points},
            reported={"png": (CAPTIONS["published"], "Validation")}),
        "validate_exudyn": ctx.step(
            "hubbeam.pipeline.jobs.reference:validate_exudyn", output={"nc": paths.exudyn_run("{vcase}")},
            log=paths.log("validation", "exudyn_{vcase}.log"),
            params={"beam": beam, "case": validation_case, "exudyn": part("exudyn"),
                    "output_step": numerics.output_step, "name": "{vcase}"},
            wildcards=per_case, constraints={"vcase": CASE_NAME_PATTERN}),
        "validate_models": ctx.step(
            f"{JOBS}:validate_models", output={"nc": paths.model_runs("{vcase}")},
            log=paths.log("validation", "models_{vcase}.log"),
            params={"beam": beam, "case": validation_case, "models": part("models"), "numerics": numerics,
                    "name": "{vcase}"},
            wildcards=per_case, constraints={"vcase": CASE_NAME_PATTERN}),
        "validate_case": ctx.step(
            f"{JOBS}:validate_case", output={"nc": paths.exudyn_case("{vcase}")},
            log=paths.log("validation", "case_{vcase}.log"),
            input={"reference": paths.exudyn_run("{vcase}"), "models": paths.model_runs("{vcase}")},
            params={"name": "{vcase}"}, wildcards=per_case, constraints={"vcase": CASE_NAME_PATTERN}),
        "validate_comparison": ctx.step(
            f"{COMPARISONS}:validate_comparison",
            output={"table": paths.exudyn_comparison("csv"), "pdf": paths.exudyn_comparison("pdf"),
                    "png": paths.exudyn_comparison("png")},
            log=paths.log("validation", "comparison.log"),
            input={"cases": [paths.exudyn_case(name) for name in names] or needs("validation.cases"),
                   "style": ctx.style},
            params={"cases": cases_or_needed}, reported={"png": (CAPTIONS["exudyn"], "Validation")}),
        "validate_modes": ctx.step(
            f"{JOBS}:validate_modes", output={"csv": paths.exudyn_mode_study()},
            log=paths.log("validation", "modes.log"),
            input={"references": [paths.exudyn_run(name) for name in names] or needs("validation.cases")},
            params={"beam": beam, "cases": validation.cases if validation is not None else needs("validation.cases"),
                    "models": part("models"), "modes": part("mode_study"), "numerics": numerics}),
        "validate_convergence": ctx.step(
            f"{JOBS}:validate_convergence",
            output={"table": paths.exudyn_convergence("csv"), "runs": paths.exudyn_convergence("nc")},
            log=paths.log("validation", "convergence.log"),
            params={"beam": beam, "case": convergence_case, "exudyn": part("exudyn"),
                    "convergence": part("convergence"), "output_step": numerics.output_step}),
        "validate_nonuniform": ctx.step(
            "hubbeam.pipeline.jobs.nonuniform:validate_nonuniform", output=nonuniform_checks(ctx),
            log=paths.log("validation", "nonuniform.log"), params={"beam": beam}),
        "validation_report": ctx.step(
            "hubbeam.pipeline.jobs.reports:validation_report",
            output={"markdown": paths.validation_report("md"), "html": paths.validation_report("html")},
            log=paths.log("report", "validation_exudyn.log"), input={**exudyn_report(ctx), **nonuniform_checks(ctx)},
            reported={"html": (CAPTIONS["report"], "Validation")}, local=True),
    }
