"""A study's report (Markdown, HTML, summary.csv; with a ``study`` section; its identification's
section from the fit and its figures), and the archive of every configuration's results: the files
of ``all``, the workflow and the completed configuration."""

from __future__ import annotations

from hubbeam.pipeline.context import PlanContext
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import PLANT_NC

REPORTS = "hubbeam.pipeline.jobs.reports"


def targets(ctx: PlanContext) -> list[str]:
    """The study report, its summary and its numbers (with a ``study`` section)."""
    paths = ctx.paths
    if ctx.settings.study is None:
        return []
    return [paths.study_report("md"), paths.study_report("html"), paths.summary(), *ctx.shaping_data().values()]


def steps(ctx: PlanContext) -> dict[str, Step]:
    paths, settings = ctx.paths, ctx.settings
    cases = [settings.case(case) for case in ctx.cases]
    fit = ctx.identification_files()
    identification = {} if not fit else {
        "identification": fit["fit"], "identification_fitted": fit["fitted"],
        "identification_figures": [ctx.identification_figure(name)[1] for name in ctx.identification_figures()]}
    return {
        "study_report": ctx.step(
            f"{REPORTS}:study_report",
            output={"markdown": paths.study_report("md"), "html": paths.study_report("html"),
                    "summary": paths.summary(), **ctx.shaping_data()},
            log=paths.log("report", "report.log"),
            input={"simulations": ctx.simulations(ctx.cases), "figures": list(ctx.figure_files("png").values()),
                   "plants": [ctx.result(PLANT_NC["plant"].replace("{plant}", plant)) for plant in settings.plants],
                   **ctx.control_report_inputs(), **identification},
            params={"study": settings.study, "beam": settings.beam, "cases": list(ctx.cases),
                    "figures": ctx.report_figures(), "control_cases": ctx.control_cases(),
                    "identification_applied": list(settings.identify.apply_to) if settings.identify else []},
            local=True, stands_for=cases),
        "archive": ctx.step(
            f"{REPORTS}:archive", output={"archive": paths.archive()}, log=paths.log("report", "archive.log"),
            input={"files": list(ctx.archived)},
            params={"config": ctx.checked.config, "paths": paths, "workflow_root": str(ctx.root)}, code=False,
            local=True, stands_for=()),
    }
