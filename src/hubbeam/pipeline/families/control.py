"""The analyses of the sampled controllers (the ``control`` section, docs/quanser-study.md): the
sample-time sweep, the robustness maps, and the implementation files of every sampled case's
controller. Their figures are products of the registry (:mod:`hubbeam.pipeline.families.figures`)."""

from __future__ import annotations

from hubbeam.model.models import model
from hubbeam.pipeline.context import PlanContext, kernel_name
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import CONTROL_FOLDER, CONTROL_NC
from hubbeam.results.paths import SHARED

JOBS = "hubbeam.pipeline.jobs.control"


def targets(ctx: PlanContext) -> list[str]:
    """The datasets of the analyses asked for and the exported controllers."""
    control = ctx.settings.control
    analyses = control.analyses if control is not None else {}
    return [ctx.result(CONTROL_NC[part]) for part in analyses] + ctx.controller_files()


def steps(ctx: PlanContext) -> dict[str, Step]:
    settings, paths = ctx.settings, ctx.paths
    analyses = settings.control.analyses if settings.control is not None else {}

    def analysis(part: str) -> Step:
        spec = analyses.get(part)
        # the sampled-loop kernels of the nonlinear confirmation runs
        families = sorted({model(settings.cases[name].model).family for name in (spec.cases if spec else ())})
        kernels = {"kernels": [SHARED.kernel_marker(kernel_name(family, True)) for family in families]}
        return ctx.step(
            f"{JOBS}:control_{part}", output={"nc": ctx.result(CONTROL_NC[part])},
            log=paths.log("control", f"{part}.log"), input=kernels if families else None,
            params={"settings": settings, "spec": spec}, wildcards=[{}] if spec is not None else [],
            stands_for=(settings.beam, settings.numerics, spec,
                        *(settings.cases[name] for name in (spec.cases if spec else ()))))

    return {
        "control_sample_time": analysis("sample_time"),
        "control_robustness": analysis("robustness"),
        "control_export": ctx.step(
            f"{JOBS}:control_export", output={ext: paths.result(CONTROL_FOLDER, f"{{case}}.{ext}")
                                              for ext in ("mat", "json")},
            log=paths.log("control", "export_{case}.log"), params={"settings": settings, "case": "{case}"},
            stands_for=(settings.beam, settings.numerics, ctx.case),
            wildcards=[{"case": case} for case in ctx.control_cases()]),
    }
