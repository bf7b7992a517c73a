"""The paper's side of the reproduction (with ``products: [paper]``): its claims against the
results, the claims under every alternative reading and their matrix, and the reproduction report
that sets every figure and number beside what the paper says."""

from __future__ import annotations

from hubbeam.model.models import FAMILIES
from hubbeam.pipeline.context import NotPlanned, PlanContext
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import PAPER_PRODUCTS, product_cases
from hubbeam.results.paths import SHARED

CLAIMS = "hubbeam.pipeline.jobs.claims"


def targets(ctx: PlanContext) -> list[str]:
    """The claims and the reproduction report with the paper's products, and the readings' matrix."""
    paths = ctx.paths
    report = [paths.claims(), paths.reproduction("md"), paths.reproduction("html")] if ctx.with_paper else []
    return report + ctx.reading_matrix()


def target_rules(ctx: PlanContext) -> dict[str, list[str]]:
    """``snakemake readings``: the claims x readings matrix alone."""
    return {"readings": ctx.reading_matrix()}


def steps(ctx: PlanContext) -> dict[str, Step]:
    paths, readings = ctx.paths, ctx.checked.readings
    claim_cases = product_cases(PAPER_PRODUCTS)

    def reading(wildcards):
        """The runs of a job's ``{reading}``."""
        if wildcards.reading not in readings:
            raise NotPlanned(f"{paths.reading(wildcards.reading)}: unknown reading {wildcards.reading!r}; "
                             f"allowed: {', '.join(readings) or 'none configured'}")
        return readings[wildcards.reading]

    def reading_cases(wildcards) -> list[str]:
        """The default runs a job's reading reads (its claims' products), sorted."""
        return sorted(reading(wildcards).bases)

    report = {"local": True}
    return {
        "claims": ctx.step(
            f"{CLAIMS}:claims", output={"claims": paths.claims()}, log=paths.log("report", "claims.log"),
            input={"datasets": ctx.simulations(claim_cases), **ctx.claim_tables()}, params={"cases": claim_cases},
            reported={"claims": ("../report/claims.rst", "Report")}, **report),
        "reading": ctx.step(
            f"{CLAIMS}:reading", output={"csv": paths.reading("{reading}")}, log=paths.log("readings", "{reading}.log"),
            input={"datasets": lambda wildcards: ctx.simulations(reading_cases(wildcards)), **ctx.claim_tables(),
                   "claims": paths.claims(), "kernel": [SHARED.kernel_marker(family) for family in FAMILIES]},
            params={"cases": reading_cases, "runs": reading}, wildcards=[{"reading": name} for name in readings],
            constraints={"reading": "[A-Za-z0-9_]+"}),
        "readings_matrix": ctx.step(
            f"{CLAIMS}:readings_matrix", output={"csv": paths.readings("csv"), "nc": paths.readings("nc")},
            log=paths.log("readings", "matrix.log"), input={"readings": [paths.reading(name) for name in readings]},
            params={"readings": ctx.settings.readings}),
        "reproduction_report": ctx.step(
            "hubbeam.pipeline.jobs.reports:reproduction_report",
            output={"markdown": paths.reproduction("md"), "html": paths.reproduction("html")},
            log=paths.log("report", "reproduction.log"),
            input={"claims": paths.claims(), "figures": list(ctx.figure_files("png").values()),
                   "tables": [paths.table(key, "md") for key in ctx.table_keys()],
                   "datasets": ctx.simulations(ctx.cases), **ctx.published_validation(),
                   **({"readings": paths.readings("csv")} if readings else {})},
            params={"cases": list(ctx.cases), "numerics": ctx.settings.numerics, "readings": ctx.settings.readings},
            reported={"html": ("../report/reproduction.rst", "Report")}, **report),
    }
