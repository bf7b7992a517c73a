"""A study's identification (its ``identify`` section, docs/identification.md): the figures of the
fit, measured against fitted per experiment and the parameters with their intervals, under
``results/<study>/identification/`` beside the fit itself. The fit (``fit.nc``) and the fitted
plant (``fitted.yaml``) are made when the plan is (:mod:`hubbeam.calibration`: the cases of
``apply_to`` are planned on its values), so no rule writes them; the figures and the study's
report read them."""

from __future__ import annotations

from hubbeam.pipeline.context import PlanContext
from hubbeam.pipeline.steps import Step

JOBS = "hubbeam.pipeline.jobs.identification"


def targets(ctx: PlanContext) -> list[str]:
    """The fit, the fitted plant and every figure of the fit (with an ``identify`` section)."""
    figures = [path for name in ctx.identification_figures() for path in ctx.identification_figure(name)]
    return [*ctx.identification_files().values(), *figures]


def steps(ctx: PlanContext) -> dict[str, Step]:
    figures = ctx.identification_figures()
    if not figures:
        return {}
    return {"identification_figures": ctx.step(
        f"{JOBS}:identification_figures",
        output={"files": [path for name in figures for path in ctx.identification_figure(name)]},
        log=ctx.paths.log("identification", "figures.log"), input={"fit": ctx.identification_files()["fit"]},
        params={"figures": figures})}
