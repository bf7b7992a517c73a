"""Benchmark hubbeam's jitted integrator against what a user would otherwise run.

    python -m hubbeam.benchmark [--configfile FILE ...] [--output DIR] [--repeats 5]
                                [--run-cap 20] [--timing-budget 10] [--skip-compilation]
                                [--skip-extras]

(``make benchmark`` runs it in the project environment.) Not part of the test suite or of the
workflow: timings depend on the machine, which is recorded beside them.

Integrators (``integrators.csv``). For every case of ``benchmark.cases`` (config) the transverse
tip deflection ``v(L)`` on the output grid is compared with a converged reference (hubbeam's Radau
IIA at ``benchmark.reference_rtol``; ``references.csv`` gives its own error estimates: the change
to a ten times looser tolerance, and the difference to scipy's Radau at that looser tolerance).
Each method searches the tolerance ladder ``benchmark.tolerances`` from the loosest rung and
stops at the first ``rtol`` (``atol = benchmark.atol_ratio * rtol`` on every free position and
velocity) that reaches ``max |v(L) - reference| <= benchmark.error_target``; its wall time is the
median of warm runs (compiled beforehand). The methods:

* ``hubbeam radau5``: hubbeam's Radau IIA kernel with dense output of the states
  (:func:`hubbeam.core.integrate.integrate_free`), and ``hubbeam simulate_kernel``: the same
  integration plus every output of a simulation dataset, at the tolerance found for the former;
* ``scipy <method>``: ``scipy.integrate.solve_ivp`` with the same equations, the jitted
  first-order right-hand side (:mod:`hubbeam.core.first_order`) as ``fun`` (a fast RHS with
  scipy's stepping) and, for ``benchmark.jacobian_methods``, the jitted forward-difference
  Jacobian as ``jac`` (otherwise scipy's own finite differences); the run is split at the end of
  the maneuver as hubbeam's is. ``benchmark.scipy_cases`` get every method of
  ``benchmark.methods``, the other cases only ``benchmark.jacobian_methods`` (the fastest);
  the ``jacobian_methods`` run a second time with the jitted Jacobian;
* one row with a plain-Python right-hand side (every jitted function replaced by its Python
  source, :func:`hubbeam.reference.pure_python`) for ``benchmark.python_rhs_case``, with the
  fastest scipy method that needs no jitted Jacobian.

A scipy run that exceeds ``--run-cap`` seconds is aborted (its row records the cap as a lower
bound, ``passed = False``), and no tighter rung is tried: a tighter tolerance never costs less.
Slow methods get fewer repetitions (``repeats`` column) so that the whole benchmark takes minutes.

Also written: ``compilation.csv`` (a fresh process's first ``simulate`` call with numba's cache
cold and warm, and the cold compile time of each kernel), ``scaling.csv`` (``simulate`` against
the number of modes and the simulated time), ``eigen.csv`` (``K22`` eigen-analyses per second),
``sweeps.csv`` (throughput and accuracy of the parameter-sweep kernel) and ``machine.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from hubbeam import __version__, eigen
from hubbeam.config import case_settings, load_config
from hubbeam.core import radau
from hubbeam.core.eom import MODEL_IDS, free_dofs
from hubbeam.core.first_order import first_order_jacobian, first_order_rhs
from hubbeam.core.integrate import (integrate_free, integration_problem, n_output_columns,
                                    output_columns, simulate_kernel, tip_watch)
from hubbeam.parameters import BeamParameters
from hubbeam.provenance import RECORDED_VERSIONS, git_commit
from hubbeam.damping import damping_matrices
from hubbeam.simulate import (case_matrices, maneuver_parameters, output_times, simulate,
                              step_stops)

DEFAULT_CONFIG = Path(__file__).resolve().parents[2] / "config" / "config.yaml"
MAX_STEPS = 10_000_000

HUBBEAM = "hubbeam radau5"
HUBBEAM_FULL = "hubbeam simulate_kernel"
JACOBIAN_NOTE = "jac = jitted forward differences (hubbeam.core.radau.jacobian)"
#: the independent check of a reference may take this many run caps
REFERENCE_CAP_FACTOR = 5


class RunTooLong(RuntimeError):
    """A scipy run exceeded its time cap (raised from inside the right-hand side)."""


@dataclass(frozen=True)
class BenchmarkCase:
    """A benchmark case prepared for every integrator: matrices, output grid, free coordinates."""

    name: str
    case: dict
    sm: tuple
    model: int
    kind: int
    mp: np.ndarray
    C: np.ndarray
    free: np.ndarray
    t: np.ndarray
    stops: np.ndarray
    watch: np.ndarray
    tip_limit: float

    @property
    def problem(self) -> tuple:
        """A fresh radau5 problem (with its work arrays) of the case, the one hubbeam runs."""
        return integration_problem(self.model, self.kind, self.mp, self.C, self.sm)


@dataclass(frozen=True)
class Method:
    """An integrator of the benchmark: ``solver`` is ``HUBBEAM``, ``HUBBEAM_FULL`` or the name
    of a ``solve_ivp`` method; ``jacobian``: pass the jitted Jacobian; ``python_rhs``: the
    plain-Python right-hand side instead of the jitted one."""

    solver: str
    jacobian: bool = False
    python_rhs: bool = False

    @property
    def label(self) -> str:
        if self.solver in (HUBBEAM, HUBBEAM_FULL):
            return self.solver
        extras = (["jitted Jacobian"] if self.jacobian else []) + (
            ["plain-Python RHS"] if self.python_rhs else [])
        return f"scipy {self.solver}" + (f" ({', '.join(extras)})" if extras else "")

    def settings(self, rtol: float, atol: float) -> str:
        parts = [f"rtol={rtol:.0e}", f"atol={atol:.0e}"]
        if self.solver == HUBBEAM_FULL:
            parts.append("all outputs of a simulation dataset")
        elif self.solver != HUBBEAM:
            parts.append("fun = " + ("plain-Python first_order_rhs" if self.python_rhs
                                     else "jitted first_order_rhs"))
            parts.append(JACOBIAN_NOTE if self.jacobian else "jac = scipy finite differences")
        return "; ".join(parts)


@dataclass(frozen=True)
class Run:
    """One integration: tip deflection on the grid (NaN where not reached), wall time, calls."""

    tip: np.ndarray
    wall: float
    rhs_calls: int
    completed: bool


def prepare_case(name: str, case: Mapping, params: BeamParameters, numerics: Mapping,
                 output_step: float) -> BenchmarkCase:
    """A :class:`BenchmarkCase` from a resolved case (``hubbeam.config.case_settings``)."""
    sm = case_matrices(case, params, numerics)
    kind, mp = maneuver_parameters(case["maneuver"])
    model = MODEL_IDS[case["model"]]
    free = free_dofs(model, kind, case["modes"])
    t = output_times(case["t_end"], output_step)
    C = damping_matrices(case.get("damping"), sm)
    return BenchmarkCase(name, dict(case), sm, model, kind, mp, C, free, t, step_stops(case, t),
                         tip_watch(free, sm), float(numerics["divergence_limit"]) * params.L)


# --------------------------------------------------------------------------- single runs
def run_hubbeam(bench: BenchmarkCase, rtol: float, atol: float, full: bool = False) -> Run:
    """hubbeam's Radau IIA: states only (:func:`integrate_free`) or every output (``full``)."""
    stats = np.zeros(len(radau.STAT_NAMES), np.int64)
    if full:
        out = np.empty((bench.t.size, n_output_columns(bench.case["modes"])))
        start = time.perf_counter()
        status, _ = simulate_kernel(bench.model, bench.kind, bench.mp, bench.C, bench.sm, bench.t,
                                    bench.stops, rtol, atol, bench.tip_limit, MAX_STEPS, out,
                                    stats)
        wall = time.perf_counter() - start
        tip = out[:, output_columns(bench.case["modes"])["tip_transverse"]]
    else:
        y_out = np.empty((bench.t.size, bench.free.size))
        v_out = np.empty_like(y_out)
        start = time.perf_counter()
        status, _, watch = integrate_free(bench.model, bench.kind, bench.mp, bench.C, bench.sm,
                                          bench.t, bench.stops, rtol, atol, bench.tip_limit,
                                          MAX_STEPS, y_out, v_out, stats)
        wall = time.perf_counter() - start
        tip = y_out @ watch
    return Run(tip, wall, int(stats[radau.RHS_CALLS]), status == radau.SUCCESS)


def _python_rhs(problem: tuple) -> Callable:
    """``first_order_rhs`` for ``problem`` with every jitted function replaced by its source."""
    from hubbeam.reference import pure_python

    fun = pure_python(first_order_rhs)
    fun.__globals__["problem_rhs"] = pure_python(radau.registered_rhs(type(problem)))
    return fun


def run_scipy(bench: BenchmarkCase, method: Method, rtol: float, atol: float,
              cap: float | None = None) -> Run:
    """``solve_ivp`` over the case, split at the end of the maneuver; ``cap`` (s) aborts the run
    with :class:`RunTooLong` (the check wraps the right-hand side, checked every 256 calls)."""
    fun = _python_rhs(bench.problem) if method.python_rhs else first_order_rhs
    if cap is not None:
        deadline = time.perf_counter() + cap
        inner, calls = fun, [0]

        def fun(t, z, problem):
            calls[0] += 1
            if calls[0] % 256 == 0 and time.perf_counter() > deadline:
                raise RunTooLong(f"{method.label} exceeded {cap} s")
            return inner(t, z, problem)

    jac = {"jac": first_order_jacobian} if method.jacobian else {}
    problem = bench.problem
    nf = bench.free.size
    edges = [bench.t[0], *bench.stops, bench.t[-1]]
    z = np.zeros(2 * nf)
    states = np.full((bench.t.size, 2 * nf), np.nan)
    nfev = njev = 0
    completed = True
    start = time.perf_counter()
    for t0, t1 in zip(edges[:-1], edges[1:]):
        inside = (bench.t >= t0) & (bench.t <= t1)
        result = solve_ivp(fun, (t0, t1), z, method=method.solver, t_eval=bench.t[inside],
                           rtol=rtol, atol=atol, args=(problem,), **jac)
        nfev += result.nfev
        njev += result.njev
        states[np.flatnonzero(inside)[:result.t.size]] = result.y.T
        if result.status != 0:
            completed = False
            break
        z = result.y[:, -1]
    wall = time.perf_counter() - start
    # the jitted Jacobian evaluates the accelerations 2N + 1 times per call, unseen by scipy
    rhs_calls = nfev + (njev * (2 * nf + 1) if method.jacobian else 0)
    return Run(states[:, :nf] @ bench.watch, wall, int(rhs_calls), completed)


def run_method(bench: BenchmarkCase, method: Method, rtol: float, atol: float,
               cap: float | None = None) -> Run:
    if method.solver in (HUBBEAM, HUBBEAM_FULL):
        return run_hubbeam(bench, rtol, atol, full=method.solver == HUBBEAM_FULL)
    return run_scipy(bench, method, rtol, atol, cap)


def max_error(tip: np.ndarray, reference: np.ndarray) -> float:
    """``max |tip - reference|`` over the grid (m); ``inf`` if the run did not reach a point."""
    difference = np.abs(np.asarray(tip) - np.asarray(reference))
    return float(np.max(difference)) if np.all(np.isfinite(difference)) else math.inf


# --------------------------------------------------------------------------- search and timing
@dataclass(frozen=True)
class Search:
    """Outcome of a tolerance search: the loosest passing ``rtol`` (None if none) and its run,
    or the last run tried; ``tried`` lists ``(rtol, max_err_m, wall_s)`` per rung."""

    rtol: float | None
    run: Run | None
    error: float
    tried: tuple
    note: str


def search_tolerance(bench: BenchmarkCase, method: Method, reference: np.ndarray,
                     ladder: Sequence[float], atol_ratio: float, target: float,
                     cap: float | None) -> Search:
    """Loosest rung of ``ladder`` (searched loose to tight) with ``max_error <= target``."""
    tried = []
    run, error = None, math.inf
    for rtol in sorted(ladder, reverse=True):
        try:
            run = run_method(bench, method, rtol, atol_ratio * rtol, cap)
        except RunTooLong:
            tried.append((rtol, math.nan, cap))
            return Search(None, None, math.inf, tuple(tried),
                          f"aborted at rtol={rtol:.0e} after the {cap:g} s cap")
        error = max_error(run.tip, reference)
        tried.append((rtol, error, run.wall))
        if error <= target:
            return Search(rtol, run, error, tuple(tried), "")
    return Search(None, run, error, tuple(tried), "no rung of the ladder reached the target")


def warm_timing(measure: Callable[[], float], first: float, repeats: int,
                budget: float) -> tuple[float, int]:
    """Median wall time of ``repeats`` warm runs, ``first`` being one of them; fewer runs when a
    run takes longer than ``budget / repeats`` (at least the first). Returns (median, count)."""
    samples = [first]
    count = max(1, min(repeats, int(budget // max(first, 1e-9))))
    while len(samples) < count:
        samples.append(measure())
    return statistics.median(samples), len(samples)


def reference_solution(bench: BenchmarkCase, rtol: float, atol_ratio: float,
                       cap: float | None) -> tuple[np.ndarray, dict]:
    """The reference tip deflection (hubbeam at ``rtol``) and its error estimates: the change
    to a ten times looser tolerance, and the difference to scipy's Radau (jitted Jacobian) at
    that looser tolerance (an independent integrator; ``cap`` seconds at most, else NaN)."""
    reference = run_hubbeam(bench, rtol, atol_ratio * rtol)
    if not reference.completed:
        raise RuntimeError(f"benchmark case {bench.name}: the reference run did not complete")
    looser = run_hubbeam(bench, 10 * rtol, 10 * atol_ratio * rtol)
    info = {"case": bench.name, "model": bench.case["model"], "rtol": rtol,
            "atol": atol_ratio * rtol, "wall_s": reference.wall, "rhs_calls": reference.rhs_calls,
            "max_abs_tip_m": float(np.max(np.abs(reference.tip))),
            "change_to_10x_looser_m": max_error(looser.tip, reference.tip),
            "scipy_radau_rtol": 10 * rtol}
    try:
        scipy_run = run_scipy(bench, Method("Radau", jacobian=True), 10 * rtol,
                              10 * atol_ratio * rtol, cap)
        info["scipy_radau_difference_m"] = max_error(scipy_run.tip, reference.tip)
        info["scipy_radau_wall_s"] = scipy_run.wall
    except RunTooLong:
        info["scipy_radau_difference_m"] = math.nan
        info["scipy_radau_wall_s"] = math.nan
    return reference.tip, info


def benchmark_case(bench: BenchmarkCase, methods: Sequence[Method], settings: Mapping,
                   repeats: int, cap: float, budget: float,
                   log=print) -> tuple[list, dict, np.ndarray]:
    """Rows of ``integrators.csv`` for one case, the reference's record and its tip deflection.

    ``HUBBEAM_FULL`` is timed at the tolerance found for ``HUBBEAM`` (listed before it)."""
    ladder, ratio = settings["tolerances"], settings["atol_ratio"]
    reference, info = reference_solution(bench, settings["reference_rtol"], ratio,
                                         REFERENCE_CAP_FACTOR * cap)
    log(f"[{bench.name}] reference: {json.dumps(info)}")
    rows = []
    hubbeam_rtol = None
    for method in methods:
        if method.solver == HUBBEAM_FULL:
            if hubbeam_rtol is None:
                continue
            run = run_method(bench, method, hubbeam_rtol, ratio * hubbeam_rtol)
            search = Search(hubbeam_rtol, run, max_error(run.tip, reference),
                            ((hubbeam_rtol, max_error(run.tip, reference), run.wall),),
                            f"at the tolerance of {HUBBEAM}")
        else:
            search = search_tolerance(bench, method, reference, ladder, ratio,
                                      settings["error_target"], cap)
        if method.solver == HUBBEAM:
            hubbeam_rtol = search.rtol
        rtol, error, wall = search.tried[-1] if search.tried else (math.nan, math.inf, math.nan)
        count = 1
        if search.rtol is not None:
            wall, count = warm_timing(lambda: run_method(bench, method, rtol, ratio * rtol).wall,
                                      search.run.wall, repeats, budget)
        rows.append({
            "case": bench.name, "model": bench.case["model"], "method": method.label,
            "modes": bench.case["modes"], "t_end_s": float(bench.t[-1]),
            "settings": method.settings(rtol, ratio * rtol), "rtol": rtol, "wall_s": wall,
            "repeats": count, "rhs_calls": search.run.rhs_calls if search.run else -1,
            "max_err_m": error, "passed": search.rtol is not None and error <= settings[
                "error_target"], "note": search.note,
            "ladder": "; ".join(f"{r:.0e}:{e:.1e}m/{w:.3g}s" for r, e, w in search.tried)})
        log(f"[{bench.name}] {method.label}: {rows[-1]['settings']}, wall {wall:.4g} s (x{count}), "
            f"err {error:.2e} m {search.note}")
    return rows, info, reference


def case_methods(settings: Mapping, name: str) -> list[Method]:
    """The methods of one case: hubbeam's, then every scipy method on ``scipy_cases`` and the
    ``jacobian_methods`` on the others, then the ``jacobian_methods`` with the jitted Jacobian."""
    scipy = settings["methods"] if name in settings["scipy_cases"] else settings[
        "jacobian_methods"]
    return ([Method(HUBBEAM), Method(HUBBEAM_FULL)] + [Method(m) for m in scipy]
            + [Method(m, jacobian=True) for m in settings["jacobian_methods"]])


def python_rhs_row(bench: BenchmarkCase, rows: Sequence[Mapping], reference: np.ndarray,
                   settings: Mapping, cap: float, log=print) -> dict:
    """The plain-Python-RHS row: the fastest passing scipy method without a jitted Jacobian,
    at the tolerance it passed with (one run, capped)."""
    candidates = [row for row in rows if row["case"] == bench.name and row["passed"]
                  and row["method"].startswith("scipy") and "Jacobian" not in row["method"]]
    if not candidates:
        raise RuntimeError(f"benchmark case {bench.name}: no scipy method passed, so there is no "
                           "method for the plain-Python RHS row")
    best = min(candidates, key=lambda row: row["wall_s"])
    method = Method(best["method"].removeprefix("scipy "), python_rhs=True)
    rtol, ratio = best["rtol"], settings["atol_ratio"]
    row = {"case": bench.name, "model": bench.case["model"], "method": method.label,
           "modes": bench.case["modes"], "t_end_s": float(bench.t[-1]),
           "settings": method.settings(rtol, ratio * rtol), "rtol": rtol, "repeats": 1,
           "ladder": ""}
    try:
        run = run_scipy(bench, method, rtol, ratio * rtol, cap)
        error = max_error(run.tip, reference)
        row |= {"wall_s": run.wall, "rhs_calls": run.rhs_calls, "max_err_m": error,
                "passed": error <= settings["error_target"],
                "note": f"tolerance of the fastest passing {best['method']} (jitted RHS)"}
    except RunTooLong:
        row |= {"wall_s": cap, "rhs_calls": -1, "max_err_m": math.inf, "passed": False,
                "note": f"aborted after the {cap:g} s cap"}
    log(f"[{bench.name}] {method.label}: wall {row['wall_s']:.4g} s {row['note']}")
    return row


# --------------------------------------------------------------------------- compilation
_FIRST_CALL = """
import json, sys, time
start = time.perf_counter()
from hubbeam.config import case_settings, load_config
from hubbeam.parameters import BeamParameters
from hubbeam.simulate import simulate
cfg = load_config(json.loads(sys.argv[1]))
case = case_settings({**cfg, "cases": {"c": json.loads(sys.argv[2])}}, "c")
params = BeamParameters.from_config(cfg)
imported = time.perf_counter()
simulate(case, params, cfg["numerics"])
first = time.perf_counter()
simulate(case, params, cfg["numerics"])
second = time.perf_counter()
from hubbeam.core.integrate import simulate_kernel
print(json.dumps({"import_s": imported - start, "first_call_s": first - imported,
                  "second_call_s": second - first,
                  "cache_misses": sum(simulate_kernel.stats.cache_misses.values()),
                  "cache_hits": sum(simulate_kernel.stats.cache_hits.values())}))
"""

_COLD_KERNEL = """
import json, sys, time
import numpy as np
from hubbeam import benchmark as b
from hubbeam.config import case_settings, load_config
from hubbeam.parameters import BeamParameters
cfg = load_config(json.loads(sys.argv[1]))
case = case_settings({**cfg, "cases": {"c": json.loads(sys.argv[2])}}, "c")
bench = b.prepare_case("c", case, BeamParameters.from_config(cfg), cfg["numerics"], 0.01)
z = np.zeros(2 * bench.free.size)
start = time.perf_counter()
if sys.argv[3] == "radau5":
    b.run_hubbeam(bench, 1e-6, 1e-8)
elif sys.argv[3] == "rhs":
    b.first_order_rhs(0.0, z, bench.problem)
else:
    b.first_order_rhs(0.0, z, bench.problem)
    b.first_order_jacobian(0.0, z, bench.problem)
print(json.dumps({"compile_s": time.perf_counter() - start}))
"""


def _subprocess_json(code: str, args: Sequence[str], cache_dir: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    env.pop("HUBBEAM_NO_JIT_CACHE", None)
    done = subprocess.run([sys.executable, "-c", code, *args], env=env, capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def compilation_rows(config_files: Sequence[str], case: Mapping) -> list[dict]:
    """Fresh processes with an empty numba cache (cold) and with the cache they left (warm)."""
    config = json.dumps([str(path) for path in config_files])
    rows = []
    case_json = json.dumps(case)
    with tempfile.TemporaryDirectory(prefix="hubbeam-numba-") as cache:
        for state in ("cold", "warm"):
            rows.append({"measurement": "fresh process, first simulate() call", "cache": state,
                         **_subprocess_json(_FIRST_CALL, [config, case_json], cache)})
    for kernel in ("radau5", "rhs", "rhs+jacobian"):
        with tempfile.TemporaryDirectory(prefix="hubbeam-numba-") as cache:
            rows.append({"measurement": f"cold compile: {kernel}", "cache": "cold",
                         **_subprocess_json(_COLD_KERNEL, [config, case_json, kernel], cache)})
    return rows


# --------------------------------------------------------------------------- extras
def _median_time(call: Callable[[], object], repeats: int, budget: float) -> tuple[float, int]:
    start = time.perf_counter()
    call()
    first = time.perf_counter() - start

    def again():
        begin = time.perf_counter()
        call()
        return time.perf_counter() - begin

    return warm_timing(again, first, repeats, budget)


def scaling_rows(cfg: Mapping, params: BeamParameters, settings: Mapping, repeats: int,
                 budget: float) -> list[dict]:
    """``simulate`` (config numerics, every output) against modes and against simulated time."""
    scaling = settings["scaling"]
    base = case_settings({**cfg, "cases": settings["cases"]}, scaling["case"])
    grid = [(n, base["t_end"]) for n in scaling["modes"]]
    grid += [(base["modes"], t_end) for t_end in scaling["t_end"] if t_end != base["t_end"]]
    rows = []
    for modes, t_end in grid:
        case = {**base, "modes": int(modes), "t_end": float(t_end)}
        result = {}

        def call():
            result["ds"] = simulate(case, params, cfg["numerics"])

        wall, count = _median_time(call, repeats, budget)
        attrs = result["ds"].attrs
        rows.append({"case": scaling["case"], "model": case["model"], "modes": modes,
                     "t_end_s": t_end, "wall_s": wall, "repeats": count,
                     "n_steps": attrs["n_steps"], "rhs_calls": attrs["n_rhs"],
                     "rtol": attrs["rtol"], "atol": attrs["atol"]})
    return rows


def eigen_rows(cfg: Mapping, params: BeamParameters, repeats: int, budget: float) -> list[dict]:
    """``K22`` eigen-analyses per second (:func:`hubbeam.eigen.k22_sweep`, all models) on the
    config's (tip mass, position, speed) grid and on a denser one."""
    grids = {"config eigen grid": (np.asarray(cfg["eigen"]["tip_masses"], float),
                                   np.linspace(**cfg["eigen"]["positions"]),
                                   np.linspace(**cfg["eigen"]["speeds"])),
             "dense grid": (np.linspace(0.0, 1.0, 20), np.linspace(**cfg["eigen"]["positions"]),
                            np.linspace(**cfg["eigen"]["speeds"]))}
    rows = []
    for label, (masses, positions, speeds) in grids.items():
        n_modes, n_quad = cfg["numerics"]["modes"], cfg["numerics"]["quadrature_points"]
        wall, count = _median_time(
            lambda: eigen.k22_sweep(params, masses, positions, speeds, n_modes, n_quad),
            repeats, budget)
        analyses = len(eigen.MODELS) * masses.size * positions.size * speeds.size
        rows.append({"grid": label, "models": len(eigen.MODELS), "tip_masses": masses.size,
                     "positions": positions.size, "speeds": speeds.size, "modes": n_modes,
                     "eigen_analyses": analyses, "wall_s": wall, "repeats": count,
                     "per_second": analyses / wall})
    return rows


def sweep_rows(cfg: Mapping, params: BeamParameters, points: int,
               reference_rtol: float) -> list[dict]:
    """For every configured sweep, a ``points x points`` sub-grid: throughput on 1 and on all
    threads, and the largest relative error of the peak tip deflection against a run at
    ``reference_rtol`` (runs that diverged in either are left out of the error)."""
    from hubbeam import sweep as sweeps

    rows = []
    threads = sweeps.default_threads()
    for name in sweeps.sweep_names(cfg):
        spec = sweeps.sweep_settings(cfg, name)
        for key in spec["axes"]:
            spec["grid"][key]["num"] = points
        timings = {}
        for count in sorted({1, threads}):
            start = time.perf_counter()
            ds = sweeps.run_sweep(spec, params, threads=count)
            timings[count] = time.perf_counter() - start
        tight = {**spec, "numerics": {**spec["numerics"], "rtol": reference_rtol,
                                      "atol": reference_rtol * spec["numerics"]["atol"]
                                      / spec["numerics"]["rtol"]}}
        exact = sweeps.run_sweep(tight, params, threads=threads)
        both = (ds.diverged == 0) & (exact.diverged == 0)
        relative = abs(ds.peak_tip_deflection / exact.peak_tip_deflection - 1.0).where(both)
        residual = abs(ds.residual_amplitude - exact.residual_amplitude).where(both)
        rows.append({"sweep": name, "simulations": int(ds.diverged.size),
                     "rtol": spec["numerics"]["rtol"], "atol": spec["numerics"]["atol"],
                     "wall_1_thread_s": timings[1], f"wall_{threads}_threads_s": timings[threads],
                     "simulations_per_s": ds.diverged.size / timings[threads],
                     "diverged": int(ds.diverged.sum()),
                     "diverged_mismatch": int((ds.diverged != exact.diverged).sum()),
                     "max_rel_err_peak": float(relative.max()),
                     "max_abs_err_residual_m": float(residual.max()),
                     "reference_rtol": reference_rtol})
    return rows


def machine_info() -> dict:
    """CPU model, cores, load, library versions and the source state of this benchmark."""
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        cpu = platform.processor() or "unknown"
    from hubbeam.sweep import default_threads

    return {
        "cpu_model": cpu,
        "logical_cpus": os.cpu_count(),
        "usable_cpus": default_threads(),
        "load_average_1_5_15": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "platform": platform.platform(),
        "python": platform.python_version(),
        **{name.lower(): metadata.version(name) for name in RECORDED_VERSIONS},
        "hubbeam": __version__,
        "git_commit": git_commit(),
        "numba_cache_dir": os.environ.get("NUMBA_CACHE_DIR"),
    }


# --------------------------------------------------------------------------- command line
def run(config_files: Sequence[str], output: Path, repeats: int, cap: float, budget: float,
        compilation: bool = True, extras: bool = True, log=print) -> dict[str, Path]:
    """Run the whole benchmark; return the files written."""
    started = time.perf_counter()
    cfg = load_config(list(config_files))
    settings = cfg["benchmark"]
    params = BeamParameters.from_config(cfg)
    output.mkdir(parents=True, exist_ok=True)
    machine = machine_info()
    log(json.dumps(machine))
    resolved = {name: case_settings({**cfg, "cases": settings["cases"]}, name)
                for name in sorted(settings["cases"])}
    benches = {name: prepare_case(name, case, params, cfg["numerics"], settings["output_step"])
               for name, case in resolved.items()}
    # compile every kernel once (not timed here: compilation.csv measures it)
    any_bench = next(iter(benches.values()))
    run_hubbeam(any_bench, 1e-3, 1e-5)
    run_hubbeam(any_bench, 1e-3, 1e-5, full=True)
    first_order_jacobian(0.0, np.zeros(2 * any_bench.free.size), any_bench.problem)
    rows, references = [], []
    for name, bench in benches.items():
        case_rows, info, reference = benchmark_case(bench, case_methods(settings, name), settings,
                                                    repeats, cap, budget, log)
        rows += case_rows
        references.append(info)
        if name == settings["python_rhs_case"]:
            rows.append(python_rhs_row(bench, case_rows, reference, settings, cap, log))
    written = {}
    columns = ["method", "settings", "wall_s", "compile_s", "rhs_calls", "max_err_m", "case",
               "model", "modes", "t_end_s", "rtol", "repeats", "passed", "note", "ladder"]
    compile_rows = []
    if compilation:
        compile_rows = compilation_rows(config_files, resolved[settings["python_rhs_case"]])
        written["compilation"] = _write_csv(compile_rows, output / "compilation.csv")
    compile_s = {row["measurement"].removeprefix("cold compile: "): row.get("compile_s")
                 for row in compile_rows if row["measurement"].startswith("cold compile")}
    first_calls = {row["cache"]: row["first_call_s"] for row in compile_rows
                   if "first_call_s" in row}
    if first_calls:  # simulate_kernel's compile time: cold minus warm first simulate() call
        compile_s[HUBBEAM_FULL] = first_calls["cold"] - first_calls["warm"]
    for row in rows:
        if row["method"] == HUBBEAM_FULL:
            row["compile_s"] = compile_s.get(HUBBEAM_FULL, math.nan)
        elif row["method"] == HUBBEAM:
            row["compile_s"] = compile_s.get("radau5", math.nan)
        elif "plain-Python" in row["method"]:
            row["compile_s"] = 0.0
        else:
            row["compile_s"] = compile_s.get("rhs+jacobian" if "Jacobian" in row["method"]
                                             else "rhs", math.nan)
    written["integrators"] = _write_csv(rows, output / "integrators.csv", columns)
    written["references"] = _write_csv(references, output / "references.csv")
    if extras:
        written["scaling"] = _write_csv(scaling_rows(cfg, params, settings, repeats, budget),
                                        output / "scaling.csv")
        written["eigen"] = _write_csv(eigen_rows(cfg, params, repeats, budget),
                                      output / "eigen.csv")
        if "sweeps" in cfg:
            check = settings["sweep_check"]
            written["sweeps"] = _write_csv(sweep_rows(cfg, params, check["points"], check["rtol"]),
                                           output / "sweeps.csv")
    machine["load_average_at_end"] = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    machine["benchmark_wall_s"] = time.perf_counter() - started
    machine["settings"] = {"repeats": repeats, "run_cap_s": cap, "timing_budget_s": budget,
                           "config_files": [str(path) for path in config_files]}
    path = output / "machine.json"
    path.write_text(json.dumps(machine, indent=2) + "\n")
    written["machine"] = path
    return written


def _write_csv(rows: Sequence[Mapping], path: Path, columns: Sequence[str] | None = None) -> Path:
    frame = pd.DataFrame(list(rows))
    if columns is not None:
        frame = frame[[column for column in columns if column in frame]]
    frame.to_csv(path, index=False)
    return path


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m hubbeam.benchmark",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--configfile", nargs="+", default=[str(DEFAULT_CONFIG)],
                        help="config file(s), merged left to right (default: %(default)s)")
    parser.add_argument("--output", type=Path, default=Path("results/benchmarks"),
                        help="directory of the CSV files and machine.json (default: %(default)s)")
    parser.add_argument("--repeats", type=int, default=5,
                        help="warm runs per timing, median reported (default: %(default)s)")
    parser.add_argument("--run-cap", type=float, default=20.0,
                        help="seconds after which a scipy run is aborted (default: %(default)s)")
    parser.add_argument("--timing-budget", type=float, default=10.0,
                        help="seconds of repeated runs per row; slower methods get fewer "
                             "repeats, at least one (default: %(default)s)")
    parser.add_argument("--skip-compilation", action="store_true",
                        help="do not time cold and warm compilation in fresh processes")
    parser.add_argument("--skip-extras", action="store_true",
                        help="skip the scaling, eigen and sweep tables")
    args = parser.parse_args(argv)
    if args.repeats < 1 or args.run_cap <= 0 or args.timing_budget <= 0:
        parser.error(f"--repeats = {args.repeats}, --run-cap = {args.run_cap}, --timing-budget "
                     f"= {args.timing_budget}; allowed: repeats >= 1, cap and budget > 0")
    written = run(args.configfile, args.output, args.repeats, args.run_cap, args.timing_budget,
                  compilation=not args.skip_compilation, extras=not args.skip_extras)
    for label, path in written.items():
        print(f"{label}: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
