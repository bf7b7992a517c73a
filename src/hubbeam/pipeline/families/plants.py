"""The plants of a study (``hubbeam.model.plant``: the arm as its cases run it, tip body, root
spring, drive and damping): per plant, what it is (its frequencies, their convergence, its critical
speeds), its tracked damped Campbell diagram, mode shapes, poles and zeros, Bode diagrams and the
exported linear models of every model, free hub (the voltage with a drive) and held. Cases that run
the same plant share its products; each plant is named after the first case that runs it. The
paper's grid of tip masses is its own family (:mod:`hubbeam.pipeline.families.linear`)."""

from __future__ import annotations

from hubbeam.linear.axes import plant_axis
from hubbeam.linear.statespace import HUBS
from hubbeam.model.models import MODELS
from hubbeam.pipeline.context import NotPlanned, PlanContext
from hubbeam.pipeline.jobs.linear import LinearExport
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import PLANT_NC

JOBS = "hubbeam.pipeline.jobs.linear"


def exports(ctx: PlanContext, plant: str) -> list[LinearExport]:
    """The exported models of ``plant``: every model, free and held hub."""
    return [LinearExport(0, model, hub, *(ctx.paths.plant_model(plant, model, hub, ext) for ext in ("nc", "mat")))
            for model in MODELS for hub in HUBS]


def plant_files(ctx: PlanContext, plant: str) -> list[str]:
    """Every product file of ``plant``."""
    return ([ctx.result(path.replace("{plant}", plant)) for path in PLANT_NC.values()]
            + [path for export in exports(ctx, plant) for path in (export.netcdf, export.matlab)])


def targets(ctx: PlanContext) -> list[str]:
    """Every product of every plant, with a ``study`` section."""
    if ctx.settings.study is None:
        return []
    return [path for plant in ctx.settings.plants for path in plant_files(ctx, plant)]


def steps(ctx: PlanContext) -> dict[str, Step]:
    settings = ctx.settings
    names = list(settings.plants) if settings.study is not None else []
    linear = settings.linear
    per_plant = [{"plant": name} for name in names]

    def axis(wildcards):
        """The plant of a job's ``{plant}`` as the axis of its datasets."""
        if wildcards.plant not in settings.plants:
            raise NotPlanned(f"unknown plant {wildcards.plant!r}; allowed: {', '.join(names) or 'none (no study)'}")
        return plant_axis(settings.plants[wildcards.plant])

    def nc(name: str) -> str:
        return ctx.result(PLANT_NC[name])

    def dataset(product: str, **params) -> Step:
        return ctx.step(f"{JOBS}:linear_dataset", output={"nc": nc(product)},
                        log=ctx.paths.log("plants", "{plant}", f"{product}.log"),
                        params={"plants": axis, "speeds": linear.speeds, "product": product, **params},
                        wildcards=per_plant)

    return {
        "plant_summary": ctx.step(
            f"{JOBS}:plant_summary", output={"nc": nc("plant")}, log=ctx.paths.log("plants", "{plant}", "plant.log"),
            params={"plant": lambda wildcards: axis(wildcards).plants[0],
                    "cases": lambda wildcards: list(settings.plant_cases[wildcards.plant][1]),
                    "search_max": settings.eigen.critical_speed_search_max},
            wildcards=per_plant),
        "plant_campbell": dataset("campbell"),
        "plant_poles_zeros": dataset("poles_zeros"),
        "plant_bode": dataset("bode", bode_speeds=list(linear.bode_speeds), frequencies=linear.frequencies),
        "plant_mode_shapes": ctx.step(
            f"{JOBS}:linear_mode_shapes", output={"nc": nc("mode_shapes")},
            log=ctx.paths.log("plants", "{plant}", "mode_shapes.log"), input={"campbell": nc("campbell")},
            params={"plants": axis, "shapes": lambda wildcards: min(linear.shapes, axis(wildcards).n_modes)},
            wildcards=per_plant),
        "plant_models": ctx.step(
            f"{JOBS}:linear_models",
            output={"files": [path for export in exports(ctx, "{plant}") for path in (export.netcdf, export.matlab)]},
            log=ctx.paths.log("plants", "{plant}", "models.log"),
            params={"plants": axis, "speeds": linear.speeds,
                    "exports": lambda wildcards: exports(ctx, wildcards.plant)},
            wildcards=per_plant),
    }
