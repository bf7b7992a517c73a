"""The simulations: the compiled kernels, the system matrices of every tip-mass configuration of the
cases, and one run per case (``simulations/<case>.nc`` of the results folder).

The matrices come from ``matrices/<configuration>.nc`` (their leading ``modes`` blocks); the beam,
the resolved case, the integrator settings and the optional convergence check come as the records
of the one check, with their fingerprint, so that editing a case reruns exactly that case. A
kernel of each family of models (and of its sampled-controller loop) compiles once, first on the
cores of a cold run; a simulation waits only for its own kernel.
"""

from __future__ import annotations

from hubbeam.model.matrices import configuration_name
from hubbeam.model.models import wildcard_pattern
from hubbeam.model.parameters import TipMass
from hubbeam.pipeline.context import KERNELS, NotPlanned, PlanContext
from hubbeam.pipeline.steps import Step
from hubbeam.results.paths import SHARED

JOBS = "hubbeam.pipeline.jobs.simulation"


def matrices_configurations(ctx: PlanContext) -> dict[str, dict]:
    """``{name: {mass, position, inertia, offset, functions, modes}}`` of the tip masses (or bodies)
    and transverse functions of the cases, each with the most modes a case using it takes (the
    others read leading blocks: the functions of a count are the first of a larger count's)."""
    configurations = {}
    for case in ctx.settings.cases.values():
        tip = case.tip_mass
        if tip.mass == 0.0 and tip.is_point:
            tip = TipMass(mass=0.0, position=ctx.settings.beam.L)
        entry = configurations.setdefault(configuration_name(tip, case.transverse_functions), {
            "mass": tip.mass, "position": tip.position, "inertia": tip.inertia, "offset": tip.offset,
            "functions": case.transverse_functions, "modes": case.modes})
        entry["modes"] = max(entry["modes"], case.modes)
    return configurations


def targets(ctx: PlanContext) -> list[str]:
    """Every run and every matrices file."""
    return ctx.simulations(ctx.cases) + [ctx.paths.matrices(name) for name in sorted(matrices_configurations(ctx))]


def steps(ctx: PlanContext) -> dict[str, Step]:
    paths, settings = ctx.paths, ctx.settings
    configurations = matrices_configurations(ctx)

    def configuration(wildcards) -> dict:
        """The tip mass and mode count of a job's ``{config_name}``."""
        if wildcards.config_name not in configurations:
            raise NotPlanned(f"{paths.matrices(wildcards.config_name)}: unknown configuration "
                             f"{wildcards.config_name!r}; allowed: {', '.join(sorted(configurations))}")
        return configurations[wildcards.config_name]

    return {
        "simulation_kernel": ctx.step(
            f"{JOBS}:simulation_kernel", output={"done": SHARED.kernel_marker("{kernel}")},
            log=SHARED.log("simulations", "kernel_{kernel}.log"),
            params={"family": _kernel_family, "sampled": _kernel_sampled},
            wildcards=[{"kernel": name} for name in KERNELS], markers=("done",), priority=100,
            constraints={"kernel": wildcard_pattern(KERNELS)}),
        "matrices": ctx.step(
            f"{JOBS}:matrices", output={"nc": paths.matrices("{config_name}")},
            log=paths.log("matrices", "{config_name}.log"),
            params={"beam": settings.beam, "configuration": configuration,
                    "n_quad": settings.numerics.quadrature_points},
            wildcards=[{"config_name": name} for name in sorted(configurations)],
            constraints={"config_name": r"mt[0-9A-Za-z_]+"}),
        "simulate": ctx.step(
            f"{JOBS}:simulate", output={"nc": paths.simulation("{case}")},
            log=paths.log("simulations", "{case}.log"),
            input={"matrices": lambda wildcards: ctx.matrices_file(ctx.case(wildcards)), "kernel": ctx.case_kernel},
            params={"beam": settings.beam, "case": ctx.case, "numerics": settings.numerics.simulation(),
                    "convergence_check": settings.numerics.convergence_check},
            wildcards=[{"case": case} for case in ctx.cases]),
    }


def _kernel_family(wildcards) -> str:
    return KERNELS[wildcards.kernel][0]


def _kernel_sampled(wildcards) -> bool:
    return KERNELS[wildcards.kernel][1]
