"""The eigen-analysis at constant hub speed of the configuration's beam with point masses: the
eigenvalues of K22 (Fig. 9), the critical speeds as a map and as the table the claims read, the
Campbell diagram of TLAM and FOAM, the beam as data and Table 2, over the grids of ``eigen``.
The products and the claims that read these files decide which are built."""

from __future__ import annotations

from hubbeam.pipeline.context import PlanContext
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import BEAM_NC, CAMPBELL_NC, CRITICAL_SPEEDS_CSV, CRITICAL_SPEEDS_NC, K22_NC, TABLE2_CSV

JOBS = "hubbeam.pipeline.jobs.eigen"
#: the transverse mode shapes of the beam's data (eigen/beam.nc, the mode-shape figure)
BEAM_MODE_SHAPES = 3


def targets(ctx: PlanContext) -> list[str]:
    """The files the products read, and the claims' tables with the paper's products."""
    read = {ctx.result(path) for product in ctx.products.values() for path in product.files.values()}
    written = {ctx.result(path) for path in (K22_NC, CAMPBELL_NC, CRITICAL_SPEEDS_NC, BEAM_NC, TABLE2_CSV,
                                             CRITICAL_SPEEDS_CSV)}
    return sorted((read & written) | (set(ctx.claim_tables().values()) if ctx.with_paper else set()))


def steps(ctx: PlanContext) -> dict[str, Step]:
    settings = ctx.settings
    eigen, beam = settings.eigen, settings.beam
    numerics = {"n_modes": settings.numerics.modes, "n_quad": settings.numerics.quadrature_points}
    search = {"search_max": eigen.critical_speed_search_max}

    def step(name: str, output: dict, **params) -> Step:
        log = ctx.paths.log("eigen", f"{name.removeprefix('eigen_')}.log")
        return ctx.step(f"{JOBS}:{name}", output=output, log=log, params={"beam": beam, **params, **numerics})

    return {
        "eigen_k22": step("eigen_k22", {"nc": ctx.result(K22_NC)}, tip_masses=list(eigen.tip_masses),
                          positions=eigen.positions, speeds=eigen.speeds),
        "eigen_critical_speeds": step("eigen_critical_speeds", {"nc": ctx.result(CRITICAL_SPEEDS_NC)},
                                      tip_masses=list(eigen.tip_masses), positions=eigen.positions, **search),
        "eigen_critical_speed_table": step("eigen_critical_speed_table", {"csv": ctx.result(CRITICAL_SPEEDS_CSV)},
                                           tip_masses=list(eigen.tip_masses), **search),
        "eigen_campbell": step("eigen_campbell", {"nc": ctx.result(CAMPBELL_NC)}, tip_masses=list(eigen.tip_masses),
                               speeds=eigen.speeds),
        "eigen_beam": step("eigen_beam", {"nc": ctx.result(BEAM_NC)},
                           tips={name: case.tip_mass for name, case in settings.cases.items()},
                           speeds=[0.0, eigen.speeds.stop], tip_masses=list(eigen.tip_masses),
                           n_shapes=BEAM_MODE_SHAPES),
        "eigen_table2": step("eigen_table2", {"csv": ctx.result(TABLE2_CSV)}, speed=eigen.table2_speed),
    }
