"""The tolerance search and the timing of the methods on one case (rows of ``integrators.csv``
and ``references.csv``)."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import partial

import numpy as np

from benchmarks.cases import (
    HUBBEAM,
    HUBBEAM_FULL,
    BenchmarkCase,
    Method,
    Run,
    RunTooLong,
    max_error,
    run_hubbeam,
    run_method,
    run_scipy,
)
from benchmarks.timing import warm_timing

#: the independent check of a reference may take this many run caps
REFERENCE_CAP_FACTOR = 5

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


def reference_solution(bench: BenchmarkCase, rtol: float, atol_ratio: float,
                       cap: float | None) -> tuple[np.ndarray, dict]:
    """The reference tip deflection (hubbeam at ``rtol``) and its error estimates: the change
    to a ten times looser tolerance, and the difference to scipy's Radau (jitted Jacobian) at
    that looser tolerance (an independent integrator; ``cap`` seconds at most, else NaN)."""
    reference = run_hubbeam(bench, rtol, atol_ratio * rtol)
    if not reference.completed:
        raise RuntimeError(f"benchmark case {bench.name}: the reference run did not complete")
    looser = run_hubbeam(bench, 10 * rtol, 10 * atol_ratio * rtol)
    info = {"case": bench.name, "model": bench.case.model, "rtol": rtol,
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

    ``HUBBEAM_FULL`` is timed at the tolerance found for ``HUBBEAM`` (listed before it); its
    ``outputs_ratio`` is its wall time over ``HUBBEAM``'s: the cost of every dataset output."""
    ladder, ratio = settings["tolerances"], settings["atol_ratio"]
    reference, info = reference_solution(bench, settings["reference_rtol"], ratio,
                                         REFERENCE_CAP_FACTOR * cap)
    log(f"[{bench.name}] reference: {json.dumps(info)}")
    rows = []
    hubbeam_rtol = None
    hubbeam_wall = math.nan
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
            wall, count = warm_timing(partial(_wall, bench, method, rtol, ratio * rtol),
                                      search.run.wall, repeats, budget)
        rows.append({
            "case": bench.name, "model": bench.case.model, "method": method.label,
            "modes": bench.case.modes, "t_end_s": float(bench.t[-1]),
            "settings": method.settings(rtol, ratio * rtol), "rtol": rtol, "wall_s": wall,
            "repeats": count, "rhs_calls": search.run.rhs_calls if search.run else -1,
            "max_err_m": error, "passed": search.rtol is not None and error <= settings[
                "error_target"], "note": search.note,
            "ladder": "; ".join(f"{r:.0e}:{e:.1e}m/{w:.3g}s" for r, e, w in search.tried)})
        if method.solver == HUBBEAM:
            hubbeam_wall = wall
        elif method.solver == HUBBEAM_FULL:
            rows[-1]["outputs_ratio"] = wall / hubbeam_wall
        log(f"[{bench.name}] {method.label}: {rows[-1]['settings']}, wall {wall:.4g} s (x{count}), "
            f"err {error:.2e} m {search.note}"
            + (f", {rows[-1]['outputs_ratio']:.2f} x {HUBBEAM}" if "outputs_ratio" in rows[-1] else ""))
    return rows, info, reference


def _wall(bench: BenchmarkCase, method: Method, rtol: float, atol: float) -> float:
    return run_method(bench, method, rtol, atol).wall


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
    row = {"case": bench.name, "model": bench.case.model, "method": method.label,
           "modes": bench.case.modes, "t_end_s": float(bench.t[-1]),
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


