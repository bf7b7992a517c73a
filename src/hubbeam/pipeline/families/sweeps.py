"""Parameter sweeps (``sweeps``): maps of the peak tip deflection. A map is split into chunks of
``chunk_size`` simulations, one job per chunk on its threads (temporary files), gathered into the
map (bit-identical to one run of the whole map) and drawn. Maps marked ``in_all: false`` are built
by ``snakemake large_sweeps``. The sweep kernel compiles once, after the simulation kernels whose
integrator it shares."""

from __future__ import annotations

from hubbeam.model.models import FAMILIES
from hubbeam.pipeline.context import NotPlanned, PlanContext, threads
from hubbeam.pipeline.steps import Step
from hubbeam.results.paths import FIGURE_FORMATS, SHARED
from hubbeam.simulation.sweep import n_chunks

SWEEPS = "hubbeam.pipeline.jobs.sweeps"


def sweep_files(ctx: PlanContext, in_all: bool) -> list[str]:
    """The map and its figure (PDF and PNG) of every sweep whose ``in_all`` is ``in_all``."""
    names = [name for name, sweep in ctx.settings.sweeps.items() if sweep.in_all == in_all]
    return [ctx.paths.sweep(name) for name in names] + [
        ctx.paths.figure(f"sweep_{name}", ext) for name in names for ext in FIGURE_FORMATS]


def targets(ctx: PlanContext) -> list[str]:
    return sweep_files(ctx, in_all=True)


def target_rules(ctx: PlanContext) -> dict[str, list[str]]:
    """``snakemake large_sweeps``: the maps too large for every run."""
    return {"large_sweeps": sweep_files(ctx, in_all=False)}


def steps(ctx: PlanContext) -> dict[str, Step]:
    paths, sweeps = ctx.paths, ctx.settings.sweeps
    pattern = {"sweep": "|".join(sweeps) or "no-sweeps"}

    def sweep(wildcards):
        """The :class:`~hubbeam.configuration.settings.Sweep` of a job's ``{sweep}``."""
        if wildcards.sweep not in sweeps:
            raise NotPlanned(f"unknown sweep {wildcards.sweep!r}; allowed: {', '.join(sweeps) or 'none configured'}")
        return sweeps[wildcards.sweep]

    def sweep_config(wildcards) -> dict:
        """The sweep of a job as its plain mapping, the param Snakemake compares for it."""
        return sweep(wildcards).to_dict()

    def chunks(wildcards) -> list[str]:
        return [paths.sweep_chunk(wildcards.sweep, str(chunk)) for chunk in range(n_chunks(sweep(wildcards)))]

    common = {"beam": ctx.settings.beam, "sweep": sweep, "sweep_config": sweep_config}
    return {
        "sweep_kernel": ctx.step(
            f"{SWEEPS}:sweep_kernel", output={"done": SHARED.sweep_kernel_marker()},
            log=SHARED.log("sweeps", "kernel.log"), markers=("done",),
            input={"simulation_kernels": [SHARED.kernel_marker(family) for family in FAMILIES]}),
        "sweep_chunk": ctx.step(
            f"{SWEEPS}:sweep_chunk", output={"nc": paths.sweep_chunk("{sweep}", "{chunk}")},
            log=paths.log("sweeps", "chunks", "{sweep}", "{chunk}.log"), input={"kernel": SHARED.sweep_kernel_marker()},
            params={**common, "chunk": "{chunk}", "threads": threads},
            wildcards=[{"sweep": name, "chunk": str(chunk)} for name, item in sweeps.items()
                       for chunk in range(n_chunks(item))],
            temporary=("nc",), constraints={**pattern, "chunk": r"\d+"}, stands_for=(ctx.settings.beam,)),
        "sweep": ctx.step(
            f"{SWEEPS}:sweep", output={"nc": paths.sweep("{sweep}")}, log=paths.log("sweeps", "{sweep}.log"),
            input={"chunks": chunks}, params=common, wildcards=[{"sweep": name} for name in sweeps],
            constraints=pattern, local=True, stands_for=(ctx.settings.beam,)),
        "figure_sweep": ctx.step(
            "hubbeam.pipeline.jobs.figures:figure_sweep", output=ctx.figure("sweep_{sweep}"),
            log=paths.log("figures", "sweep_{sweep}.log"), input={"sweep": paths.sweep("{sweep}"), "style": ctx.style},
            wildcards=[{"sweep": name} for name in sweeps], constraints=pattern, local=True,
            reported={"png": ("../report/sweep.rst", "Beyond the paper")}),
    }
