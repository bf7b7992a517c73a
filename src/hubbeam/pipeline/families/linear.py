"""The linear models about a steady spin for control design (docs/linear-models.md), from the
``linear`` section: the state-space models of every model, free and prescribed hub, over the speed
grid as CF netCDF and MATLAB files, and the datasets the linear-model figures of the registry read
(the tracked, damped Campbell diagram, the mode shapes along the span, the poles and zeros over
speed and the Bode diagrams)."""

from __future__ import annotations

from hubbeam.linear.axes import tip_mass_axis
from hubbeam.linear.statespace import HUBS
from hubbeam.model.models import MODELS
from hubbeam.pipeline.context import PlanContext
from hubbeam.pipeline.jobs.linear import LinearExport
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import LINEAR_NC

JOBS = "hubbeam.pipeline.jobs.linear"


def exports(ctx: PlanContext) -> list[LinearExport]:
    """Every model and hub condition at every tip mass of ``linear.tip_masses`` (none for a study,
    whose plants have their own: :mod:`hubbeam.pipeline.families.plants`)."""
    if ctx.settings.study is not None:
        return []
    return [LinearExport(k, name, hub, *(ctx.paths.linear_model(name, hub, k, ext) for ext in ("nc", "mat")))
            for k in range(len(ctx.settings.linear.tip_masses)) for name in MODELS for hub in HUBS]


def targets(ctx: PlanContext) -> list[str]:
    """The exported models and the datasets the products read (none for a study)."""
    read = {ctx.result(path) for product in ctx.products.values() for path in product.files.values()}
    return [path for export in exports(ctx) for path in (export.netcdf, export.matlab)] + sorted(
        read & {ctx.result(path) for path in LINEAR_NC.values()})


def steps(ctx: PlanContext) -> dict[str, Step]:
    settings = ctx.settings
    if settings.study is not None:
        return {}
    linear, numerics = settings.linear, settings.numerics
    plants = tip_mass_axis(settings.beam, linear.tip_masses, numerics.modes, numerics.quadrature_points,
                           linear.damping)
    common = {"plants": plants, "speeds": linear.speeds}

    def dataset(product, **params):
        return ctx.step(f"{JOBS}:linear_dataset", output={"nc": ctx.result(LINEAR_NC[product])},
                        log=ctx.paths.log("linear", f"{product}.log"), params={**common, "product": product, **params})

    files = [path for export in exports(ctx) for path in (export.netcdf, export.matlab)]
    return {
        "linear_models": ctx.step(
            f"{JOBS}:linear_models", output={"files": files}, log=ctx.paths.log("linear", "models.log"),
            params={**common, "exports": exports(ctx)}),
        "linear_campbell": dataset("campbell"),
        "linear_poles_zeros": dataset("poles_zeros"),
        "linear_bode": dataset("bode", bode_speeds=list(linear.bode_speeds), frequencies=linear.frequencies),
        "linear_mode_shapes": ctx.step(
            # no more than the vibration modes every model has (SFOAM: numerics.modes)
            f"{JOBS}:linear_mode_shapes", output={"nc": ctx.result(LINEAR_NC["mode_shapes"])},
            log=ctx.paths.log("linear", "mode_shapes.log"), input={"campbell": ctx.result(LINEAR_NC["campbell"])},
            params={"plants": plants, "shapes": min(linear.shapes, numerics.modes)}),
    }
