"""Parameter sweeps: maps of the peak tip deflection over maneuver or tip-mass parameters.

A sweep (``sweeps.maps.<name>`` of the config, a :class:`hubbeam.configuration.settings.Sweep`
built once with the configuration's settings, ``Settings.sweeps``) fixes the models, the maneuver
kind and its fixed parameters, the tip mass, and spans two or more swept parameters (``wf``,
``tf``, ``tau_max``, ``tip_mass``, ``tip_position``) on uniform grids. Every (model, grid point)
is one simulation from rest over ``[0, tf + t_after]``, run by the parallel kernel
:func:`hubbeam.core.sweep.sweep_tip_extrema` (the integrator and equations of
:func:`hubbeam.simulation.simulate.simulate`, keeping only the extrema of the tip deflection).
:func:`run_sweep` returns a self-describing dataset over ``(model, <axis 1>, <axis 2>, ...)``; a
run that stops early (tip deflection beyond ``numerics.divergence_limit * L``, a non-finite state
or a vanishing step) is a result with NaN extrema, classified by :mod:`hubbeam.model.validity`
(variable ``validity``: valid, large_deflection, left_range or diverged).

A map is also computed in chunks of ``chunk_size`` consecutive points (in the C order of
``(model, axes...)``): :func:`run_chunk` simulates one chunk into a small dataset of raw per-point
arrays, :func:`gather_chunks` joins them into the map. Every point is simulated alone, so the
gathered map is bit-identical to :func:`run_sweep`'s, whatever the chunk size.
"""

from __future__ import annotations

import json
import logging
import os
import time
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import xarray as xr

from hubbeam.configuration.settings import Grid, Sweep, SweepNumerics
from hubbeam.core import radau
from hubbeam.core import sweep as kernels
from hubbeam.core.inputs import IntegratorSettings
from hubbeam.model import eigen, validity
from hubbeam.model.beam import beam_attributes
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.maneuvers import MANEUVERS
from hubbeam.model.matrices import SystemMatrices, assemble
from hubbeam.model.models import model
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.results.provenance import global_attributes
from hubbeam.simulation.simulate import INTEGRATOR, kernel_matrices

LOG = logging.getLogger(__name__)

#: parameters a sweep may span: (units, long name)
PARAMETERS = {
    "wf": ("rad s-1", "final hub angular velocity w_f of the spin-up (Eq. 43)"),
    "tf": ("s", "maneuver time t_f (spin-up duration, Eq. 43, or torque-pulse period, Eq. 44)"),
    "tau_max": ("N m", "torque-pulse amplitude tau_m (Eq. 44)"),
    "tip_mass": ("kg", "tip mass m_t"),
    "tip_position": ("m", "tip-mass position l from the clamped root"),
}
TIP_PARAMETERS = ("tip_mass", "tip_position")

#: outputs a sweep may store: (column of the kernel's result array, units, long name)
OUTPUTS = {
    "peak_tip_deflection": (kernels.PEAK, "m",
                            "peak transverse tip deflection max |v(L)| over [0, t_end]"),
    "peak_time": (kernels.PEAK_TIME, "s", "time of the peak transverse tip deflection"),
    "residual_amplitude": (kernels.RESIDUAL, "m",
                           "residual vibration amplitude max |v(L)| over [t_f, t_end]"),
}


def axis_values(sweep: Sweep) -> dict[str, np.ndarray]:
    """``{swept parameter: grid values}`` in the order of the sweep's axes."""
    return {key: grid.values for key, grid in sweep.grid.items()}


def _points(sweep: Sweep):
    """Per-point inputs of the kernel, points ordered as ``(model, axes...)`` in C order.

    Returns ``traits`` (the kernels' model traits of every point as rows,
    :class:`hubbeam.core.sweep.SweepPoints`), ``mp, matrix_index, t_end, t_mark`` and the
    distinct tip masses as a list of ``TipMass`` (``matrix_index`` points into it).
    """
    axes = axis_values(sweep)
    models = np.array([model(name).traits for name in sweep.models], dtype=bool)
    shape = (len(models),) + tuple(values.size for values in axes.values())
    grids = dict(zip(axes, np.meshgrid(*axes.values(), indexing="ij")))

    def value(key, fixed):
        swept = grids.get(key)
        return np.broadcast_to(swept if swept is not None else fixed, shape[1:])

    maneuver = sweep.maneuver
    mp = np.stack([value(key, maneuver.get(key)) for key in MANEUVERS[maneuver["kind"]].kernel_keys],
                  axis=-1).astype(float)
    tf = value("tf", maneuver.get("tf")).astype(float)
    tips = np.stack([value("tip_mass", sweep.tip_mass.mass),
                     value("tip_position", sweep.tip_mass.position)], axis=-1).astype(float)
    distinct, inverse = np.unique(tips.reshape(-1, 2), axis=0, return_inverse=True)

    def per_point(array):  # (grid..., extra...) -> (model x grid, extra...): a writable copy
        extra = array.shape[len(shape) - 1:]
        return np.array(np.broadcast_to(array, (len(models),) + array.shape).reshape((-1,) + extra),
                        order="C")

    return (np.repeat(models, np.prod(shape[1:], dtype=int), axis=0), per_point(mp),
            per_point(inverse.reshape(shape[1:])), per_point(tf + sweep.t_after),
            per_point(tf), [TipMass(float(m), float(l)) for m, l in distinct])


def matrix_stack(matrices: list[SystemMatrices]) -> SystemMatrices:
    """One :class:`SystemMatrices` whose fields stack those of ``matrices`` along a new first
    axis (scalars become 1-D arrays), as :func:`hubbeam.core.sweep.matrices_at` reads it."""
    matrices = [kernel_matrices(sm) for sm in matrices]
    return SystemMatrices(*(np.ascontiguousarray(np.stack([np.asarray(field, float)
                                                           for field in fields]))
                            for fields in zip(*matrices)))


def default_threads() -> int:
    """The CPUs this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()


def n_points(sweep: Sweep) -> int:
    """Simulations of the sweep: models times grid points."""
    return len(sweep.models) * int(np.prod([grid.num for grid in sweep.grid.values()]))


def n_chunks(sweep: Sweep) -> int:
    """Chunks of ``sweep.chunk_size`` consecutive points that cover the sweep."""
    return -(-n_points(sweep) // sweep.chunk_size)


def chunk_points(sweep: Sweep, index: int) -> range:
    """The points (C order of ``(model, axes...)``) of chunk ``index``."""
    if not 0 <= index < n_chunks(sweep):
        raise IndexError(f"sweep {sweep.name}: chunk {index}; allowed: 0 to "
                         f"{n_chunks(sweep) - 1}")
    size = sweep.chunk_size
    return range(index * size, min((index + 1) * size, n_points(sweep)))


def run_points(sweep: Sweep, params: BeamParameters, points: range | None = None,
               threads: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Simulate the ``points`` of the resolved ``sweep`` (default: all) on ``threads`` threads
    (default: every CPU this process may use); return the kernel's per-point ``results``,
    ``status`` and ``stats`` arrays. The numbers do not depend on the thread count or on which
    other points run alongside."""
    traits, mp, matrix_index, t_end, t_mark, tips = _points(sweep)
    points = range(len(traits)) if points is None else points
    selected = slice(points.start, points.stop)
    used, local_index = np.unique(matrix_index[selected], return_inverse=True)
    stack = matrix_stack([assemble(params, tips[k], sweep.modes, sweep.quadrature_points)
                          for k in used])
    numerics = sweep.numerics
    count = len(points)
    threads = max(1, min(int(threads or default_threads()), count))
    found = kernels.SweepResults(np.full((count, len(kernels.RESULT_COLUMNS)), np.nan),
                                 np.zeros(count, np.int64), np.zeros((count, kernels.N_STATS), np.int64))
    sweep_points = kernels.SweepPoints(
        np.ascontiguousarray(traits[selected]), MANEUVERS[sweep.maneuver["kind"]].code,
        np.ascontiguousarray(mp[selected]), np.ascontiguousarray(local_index.ravel()),
        np.ascontiguousarray(t_end[selected]), np.ascontiguousarray(t_mark[selected]))
    settings = IntegratorSettings(float(numerics.rtol), float(numerics.atol),
                                  float(sweep.divergence_limit * params.L), int(numerics.max_steps))
    arguments = (sweep_points, stack, float(numerics.output_step), settings, found)
    start = time.perf_counter()
    with ThreadPoolExecutor(threads) as pool:
        shares = [pool.submit(kernels.sweep_tip_extrema, first, threads, *arguments)
                  for first in range(threads)]
        for share in shares:
            share.result()
    wall = time.perf_counter() - start
    results, status, stats = found
    LOG.info("sweep %s, points %d to %d: %d simulations in %.2f s on %d threads (%.2f ms each), "
             "%d stopped early, %d failed, %d rhs calls", sweep.name, points.start, points.stop - 1,
             count, wall, threads, 1e3 * wall / max(count, 1),
             np.isin(status, (radau.LEFT_RANGE, *validity.BLOWN_UP)).sum(),
             (status == radau.TOO_MANY_STEPS).sum(),
             stats[:, radau.RHS_CALLS].sum())
    return results, status, stats


def run_sweep(sweep: Sweep, params: BeamParameters, threads: int | None = None) -> xr.Dataset:
    """Simulate every point of the resolved ``sweep`` in one go (:func:`run_points`) and return
    the sweep dataset."""
    return build_dataset(sweep, params, *run_points(sweep, params, threads=threads))


def run_chunk(sweep: Sweep, params: BeamParameters, index: int,
              threads: int | None = None) -> xr.Dataset:
    """Chunk ``index`` of the sweep (:func:`chunk_points`): the kernel's raw arrays over its
    points, for :func:`gather_chunks`."""
    points = chunk_points(sweep, index)
    results, status, stats = run_points(sweep, params, points, threads)
    return xr.Dataset(
        {"results": (("point", "result_column"), results),
         "status": ("point", status),
         "stats": (("point", "stat"), stats)},
        coords={"point": ("point", np.arange(points.start, points.stop)),
                "result_column": list(kernels.RESULT_COLUMNS), "stat": list(radau.STAT_NAMES)},
        attrs={"sweep_name": sweep.name, "chunk": index, "n_chunks": n_chunks(sweep),
               "sweep_config": json.dumps(sweep.to_dict(), sort_keys=True)})


def gather_chunks(sweep: Sweep, params: BeamParameters, chunks: list[xr.Dataset]) -> xr.Dataset:
    """The sweep dataset from every chunk of :func:`run_chunk` (any order); the chunks must be
    of this very sweep and cover it exactly once."""
    config = json.dumps(sweep.to_dict(), sort_keys=True)
    chunks = sorted(chunks, key=lambda chunk: int(chunk.attrs["chunk"]))
    found = [int(chunk.attrs["chunk"]) for chunk in chunks]
    if found != list(range(n_chunks(sweep))):
        raise ValueError(f"sweep {sweep.name}: chunks {found}; allowed: each of 0 to "
                         f"{n_chunks(sweep) - 1} once")
    for chunk in chunks:
        if chunk.attrs["sweep_config"] != config:
            raise ValueError(f"sweep {sweep.name}: chunk {int(chunk.attrs['chunk'])} was run "
                             "with other sweep settings; allowed: chunks of the same settings")
    return build_dataset(sweep, params,
                         *(np.concatenate([chunk[name].values for chunk in chunks])
                           for name in ("results", "status", "stats")))


def build_dataset(sweep: Sweep, params: BeamParameters, results: np.ndarray,
                  status: np.ndarray, stats: np.ndarray) -> xr.Dataset:
    """The labelled sweep dataset from the kernel's per-point arrays (points in C order of
    ``(model, axes...)``)."""
    axes = axis_values(sweep)
    dims = ("model",) + tuple(axes)
    shape = (len(sweep.models),) + tuple(values.size for values in axes.values())
    status = status.reshape(shape)
    critical = _critical_speeds(sweep, params, axes)
    codes = _validity(sweep, params, status, results[:, kernels.PEAK].reshape(shape), critical, dims)
    diverged = codes == validity.DIVERGED
    stopped = "NaN where the run stopped early (see validity and status)"
    data_vars = {
        name: (dims, results[:, OUTPUTS[name][0]].reshape(shape),
               {"units": OUTPUTS[name][1], "long_name": OUTPUTS[name][2], "comment": stopped})
        for name in sweep.outputs
    }
    data_vars["validity"] = (dims, codes.astype(np.int8), {
        "units": "1", "long_name": "validity of the run (hubbeam.model.validity): within the small-"
        "deflection range, beyond it, stopped outside the range of the models, or diverged "
        "beyond the critical speed", "flag_values": np.arange(len(validity.CATEGORIES), dtype=np.int8),
        "flag_meanings": " ".join(validity.CATEGORIES)})
    data_vars["diverged"] = (dims, diverged.astype(np.int8), {
        "units": "1", "long_name": "run diverged (beyond the critical speed of its linearisation, "
        "non-finite state or vanishing step size)", "flag_values": np.array([0, 1], np.int8),
        "flag_meanings": "bounded diverged"})
    data_vars["status"] = (dims, status.astype(np.int8), {
        "units": "1", "long_name": "integrator status",
        "flag_values": np.arange(len(radau.STATUS_NAMES), dtype=np.int8),
        "flag_meanings": " ".join(radau.STATUS_NAMES)})
    data_vars["stopped_at"] = (dims, results[:, kernels.T_STOP].reshape(shape), {
        "units": "s", "long_name": "time the run ended (t_end unless it stopped early)"})
    for name, column, long_name in (
            ("n_steps", radau.ACCEPTED, "accepted integrator steps"),
            ("n_rhs", radau.RHS_CALLS, "right-hand-side evaluations (incl. Jacobians)")):
        data_vars[name] = (dims, stats[:, column].reshape(shape).astype(np.int32),
                           {"units": "1", "long_name": long_name})
    data_vars["critical_speed"] = critical
    coords = {"model": ("model", list(sweep.models), {"long_name": "model (Section 3)"}),
              "eigen_model": ("eigen_model", list(eigen.LINEARISATIONS),
                              {"long_name": "model of the eigen-analysis (Eq. 31)"})}
    for key, values in axes.items():
        units, long_name = PARAMETERS[key]
        coords[key] = (key, values, {"units": units, "long_name": long_name})
    numerics = sweep.numerics
    failed = int((status == radau.TOO_MANY_STEPS).sum())
    attributes = {
        "sweep_name": sweep.name,
        "sweep_config": sweep.to_dict(),
        "integrator": INTEGRATOR,
        "rtol": float(numerics.rtol),
        "atol": float(numerics.atol),
        "output_step": float(numerics.output_step),
        "max_steps": int(numerics.max_steps),
        "divergence_limit": float(sweep.divergence_limit),
        "t_after_s": float(sweep.t_after),
        "n_modes": int(sweep.modes),
        "n_simulations": int(status.size),
        "n_diverged": int(diverged.sum()),
        "n_left_range": int((codes == validity.LEFT_RANGE).sum()),
        "n_large_deflection": int((codes == validity.LARGE_DEFLECTION).sum()),
        "small_deflection_limit": float(sweep.small_deflection_limit),
        "n_failed": failed,
        **beam_attributes(params),
        "warnings": (f"{failed} runs exhausted the step budget max_steps = "
                     f"{numerics.max_steps} (status too_many_steps)" if failed else ""),
    }
    title = (f"hubbeam sweep {sweep.name}: {', '.join(sweep.models)}, "
             f"{json.dumps(dict(sweep.maneuver))} over {' x '.join(axes)}")
    return xr.Dataset(data_vars, coords=coords, attrs=global_attributes(title, extra=attributes))


def _validity(sweep: Sweep, params: BeamParameters, status: np.ndarray, peak: np.ndarray,
              critical: xr.Variable, dims: tuple) -> np.ndarray:
    """The :mod:`hubbeam.model.validity` category of every run, over ``(model, axis 1, axis 2)``.

    A run's linearised stiffness is lost when its hub speed ``wf`` (swept or fixed) exceeds the
    critical speed of its model's linearisation (``critical``, over the swept tip parameters); a
    maneuver without ``wf`` (a torque pulse) keeps no hub speed, and its stop counts as a
    divergence exactly for a model whose linearisation has a critical speed (TLAM)."""
    axes = axis_values(sweep)
    critical = xr.DataArray(critical, coords={"eigen_model": list(eigen.LINEARISATIONS),
                                              **{key: axes[key] for key in critical.dims if key in axes}})
    cells = xr.DataArray(np.zeros(status.shape), dims=dims,
                         coords={"model": list(sweep.models), **axes})
    limit = xr.concat([critical.sel(eigen_model=model(name).linearisation, drop=True)
                       for name in sweep.models], dim="model")
    limit = (limit.assign_coords(model=list(sweep.models)) + cells).transpose(*dims).values
    if "wf" in axes:
        speed = (cells + cells["wf"]).transpose(*dims).values
    else:
        speed = np.full(status.shape, sweep.maneuver.get("wf", np.inf))
    lost = speed > np.nan_to_num(limit, nan=np.inf)
    ratio = peak / params.L
    return np.vectorize(validity.classify, otypes=[np.int8])(
        status, lost, ratio, sweep.small_deflection_limit)


def _critical_speeds(sweep: Sweep, params: BeamParameters, axes: Mapping):
    """Critical speeds of TLAM and FOAM (:func:`hubbeam.model.eigen.critical_speed_sweep`) at the
    sweep's tip masses and positions, over the swept tip parameters (a dataset variable)."""
    masses = axes.get("tip_mass", np.array([sweep.tip_mass.mass]))
    positions = axes.get("tip_position", np.array([sweep.tip_mass.position]))
    critical = eigen.critical_speed_sweep(params, masses, positions, sweep.modes,
                                          sweep.critical_speed_search_max,
                                          sweep.quadrature_points)["critical_speed"]
    critical = critical.rename(model="eigen_model", position="tip_position")
    critical = critical.isel({key: 0 for key in TIP_PARAMETERS if key not in axes})
    dims = ("eigen_model",) + tuple(key for key in critical.dims if key != "eigen_model")
    return xr.Variable(dims, critical.transpose(*dims).values, {
        "units": "rad s-1", "long_name": "critical angular velocity of K22 (Eq. 31) at the "
        "sweep's tip mass; NaN: none up to critical_speed_search_max (always for FOAM)"})


def compile_kernel() -> float:
    """Compile (or load from numba's cache) the sweep kernel; return the seconds it took."""
    params = BeamParameters(L=1.0, rho=1.0, A=1.0, E=1.0, I=1.0, Jh=1.0, rA=0.1)
    sweep = Sweep(name="compile_kernel", models=("FOAM",), maneuver=FrozenMap({"kind": "prescribed"}),
                  grid=FrozenMap({"wf": Grid(0.1, 0.1, 1), "tf": Grid(0.05, 0.05, 1)}), t_after=0.05, modes=1,
                  tip_mass=TipMass(0.0, 1.0), outputs=(), figure=FrozenMap(), in_all=True, chunk_size=1,
                  numerics=SweepNumerics(rtol=1e-6, atol=1e-8, output_step=0.05, max_steps=1000),
                  divergence_limit=1.0, small_deflection_limit=0.1, quadrature_points=8,
                  critical_speed_search_max=1.0)
    start = time.perf_counter()
    run_points(sweep, params, threads=1)
    return time.perf_counter() - start
