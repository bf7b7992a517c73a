"""The tables beside the integrator comparison: ``scaling.csv`` (``simulate`` against modes and
simulated time), ``eigen.csv`` (``K22`` eigen-analyses per second) and ``sweeps.csv``
(throughput and accuracy of the parameter-sweep kernel)."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping
from functools import partial

import numpy as np

from benchmarks.timing import median_time
from hubbeam.configuration.settings import case_from_config, from_config
from hubbeam.core import radau
from hubbeam.model import eigen
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.parameters import BeamParameters
from hubbeam.simulation import sweep as sweeps
from hubbeam.simulation.simulate import simulate


def _append_simulation(results: list, case: Mapping, params: BeamParameters, numerics: Mapping) -> None:
    results.append(simulate(case, params, numerics))


def scaling_rows(cfg: Mapping, params: BeamParameters, settings: Mapping, repeats: int,
                 budget: float) -> list[dict]:
    """``simulate`` (config numerics, every output) against modes and against simulated time."""
    scaling = settings["scaling"]
    base = case_from_config({**cfg, "cases": settings["cases"]}, scaling["case"])
    grid = [(n, base.t_end) for n in scaling["modes"]]
    grid += [(base.modes, t_end) for t_end in scaling["t_end"] if t_end != base.t_end]
    rows = []
    for modes, t_end in grid:
        case = dataclasses.replace(base, modes=int(modes), t_end=float(t_end))
        results = []
        wall, count = median_time(partial(_append_simulation, results, case, params, cfg["numerics"]),
                                  repeats, budget)
        attrs = results[-1].attrs
        rows.append({"case": scaling["case"], "model": case.model, "modes": modes,
                     "t_end_s": t_end, "wall_s": wall, "repeats": count,
                     "n_steps": attrs["n_steps"], "rhs_calls": attrs["n_rhs"],
                     "rtol": attrs["rtol"], "atol": attrs["atol"]})
    return rows


def eigen_rows(cfg: Mapping, params: BeamParameters, repeats: int, budget: float) -> list[dict]:
    """``K22`` eigen-analyses per second (:func:`hubbeam.model.eigen.k22_sweep`, all models) on the
    config's (tip mass, position, speed) grid and on a denser one."""
    grids = {"config eigen grid": (np.asarray(cfg["eigen"]["tip_masses"], float),
                                   np.linspace(**cfg["eigen"]["positions"]),
                                   np.linspace(**cfg["eigen"]["speeds"])),
             "dense grid": (np.linspace(0.0, 1.0, 20), np.linspace(**cfg["eigen"]["positions"]),
                            np.linspace(**cfg["eigen"]["speeds"]))}
    rows = []
    for label, (masses, positions, speeds) in grids.items():
        n_modes, n_quad = cfg["numerics"]["modes"], cfg["numerics"]["quadrature_points"]
        wall, count = median_time(
            partial(eigen.k22_sweep, params, masses, positions, speeds, n_modes, n_quad), repeats, budget)
        analyses = len(eigen.LINEARISATIONS) * masses.size * positions.size * speeds.size
        rows.append({"grid": label, "models": len(eigen.LINEARISATIONS), "tip_masses": masses.size,
                     "positions": positions.size, "speeds": speeds.size, "modes": n_modes,
                     "eigen_analyses": analyses, "wall_s": wall, "repeats": count,
                     "per_second": analyses / wall})
    return rows


def sweep_rows(cfg: Mapping, params: BeamParameters, points: int,
               reference_rtol: float) -> list[dict]:
    """For every configured sweep, a ``points x points`` sub-grid: throughput on 1 and on all
    threads, and the largest relative error of the peak tip deflection against a run at
    ``reference_rtol`` (runs stopped early in either are left out of the error)."""

    rows = []
    threads = sweeps.default_threads()
    for name, configured in from_config(cfg).sweeps.items():
        spec = dataclasses.replace(configured, grid=FrozenMap({key: dataclasses.replace(grid, num=points)
                                                               for key, grid in configured.grid.items()}))
        timings = {}
        for count in sorted({1, threads}):
            start = time.perf_counter()
            ds = sweeps.run_sweep(spec, params, threads=count)
            timings[count] = time.perf_counter() - start
        tight = dataclasses.replace(spec, numerics=dataclasses.replace(
            spec.numerics, rtol=reference_rtol, atol=reference_rtol * spec.numerics.atol / spec.numerics.rtol))
        exact = sweeps.run_sweep(tight, params, threads=threads)
        both = (ds.status == radau.SUCCESS) & (exact.status == radau.SUCCESS)
        relative = abs(ds.peak_tip_deflection / exact.peak_tip_deflection - 1.0).where(both)
        # a sweep that does not store the residual amplitude has no error for it (NaN)
        residual = (abs(ds.residual_amplitude - exact.residual_amplitude).where(both).max()
                    if "residual_amplitude" in ds else np.nan)
        rows.append({"sweep": name, "simulations": int(ds.diverged.size),
                     "rtol": spec.numerics.rtol, "atol": spec.numerics.atol,
                     "wall_1_thread_s": timings[1], f"wall_{threads}_threads_s": timings[threads],
                     "simulations_per_s": ds.diverged.size / timings[threads],
                     "diverged": int(ds.diverged.sum()),
                     "diverged_mismatch": int((ds.diverged != exact.diverged).sum()),
                     "max_rel_err_peak": float(relative.max()),
                     "max_abs_err_residual_m": float(residual),
                     "reference_rtol": reference_rtol})
    return rows
