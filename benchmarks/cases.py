"""One benchmark case and single runs of it: hubbeam's Radau IIA kernels and
``scipy.integrate.solve_ivp`` with the jitted (or plain-Python) first-order right-hand side."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from hubbeam.configuration.settings import Numerics
from hubbeam.core import radau
from hubbeam.core.eom import free_dofs
from hubbeam.core.first_order import first_order_jacobian, first_order_rhs
from hubbeam.core.inputs import IntegratorSettings, SimulationInputs, State, Trajectory
from hubbeam.core.integrate import (
    integrate_free,
    integration_problem,
    n_output_columns,
    output_columns,
    simulate_kernel,
    tip_watch,
)
from hubbeam.model.damping import damping_matrices
from hubbeam.model.models import model
from hubbeam.model.parameters import BeamParameters
from hubbeam.simulation.simulate import (
    case_matrices,
    initial_state,
    output_times,
    step_stops,
)

MAX_STEPS = 10_000_000

HUBBEAM = "hubbeam radau5"
HUBBEAM_FULL = "hubbeam simulate_kernel"
JACOBIAN_NOTE = "jac = jitted forward differences (hubbeam.core.radau.jacobian)"


class RunTooLong(RuntimeError):
    """A scipy run exceeded its time cap (raised from inside the right-hand side)."""


@dataclass(frozen=True)
class BenchmarkCase:
    """A benchmark case prepared for every integrator: matrices, output grid, free coordinates."""

    name: str
    case: dict
    inputs: SimulationInputs
    start: State
    free: np.ndarray
    t: np.ndarray
    stops: np.ndarray
    watch: np.ndarray
    tip_limit: float

    @property
    def problem(self) -> tuple:
        """A fresh radau5 problem (with its work arrays) of the case, the one hubbeam runs."""
        return integration_problem(self.inputs)

    def settings(self, rtol: float, atol: float) -> IntegratorSettings:
        """hubbeam's integrator settings of a run at ``rtol``, ``atol``."""
        return IntegratorSettings(float(rtol), float(atol), self.tip_limit, MAX_STEPS)


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
    """A :class:`BenchmarkCase` from a resolved :class:`~hubbeam.configuration.settings.Case`."""
    numerics = Numerics.from_mapping(numerics)
    sm = case_matrices(case, params, numerics)
    kind, mp = case.maneuver.kernel_parameters()
    inputs = SimulationInputs(model(case.model).traits, kind, mp, damping_matrices(case.damping, sm), sm)
    free = free_dofs(inputs.traits, kind, case.modes)
    t = output_times(case.t_end, output_step)
    return BenchmarkCase(name, case, inputs, initial_state(case, sm), free, t,
                         step_stops(case.maneuver, t), tip_watch(free, sm),
                         float(numerics.divergence_limit) * params.L)


# --------------------------------------------------------------------------- single runs
def run_hubbeam(bench: BenchmarkCase, rtol: float, atol: float, full: bool = False) -> Run:
    """hubbeam's Radau IIA: states only (:func:`integrate_free`) or every output (``full``)."""
    stats = np.zeros(len(radau.STAT_NAMES), np.int64)
    if full:
        out = np.empty((bench.t.size, n_output_columns(bench.case.modes)))
        start = time.perf_counter()
        status, _ = simulate_kernel(bench.inputs, bench.start, bench.t, bench.stops,
                                    bench.settings(rtol, atol), out, stats)
        wall = time.perf_counter() - start
        tip = out[:, output_columns(bench.case.modes)["tip_transverse"]]
    else:
        y_out = np.empty((bench.t.size, bench.free.size))
        v_out = np.empty_like(y_out)
        start = time.perf_counter()
        status, _, watch = integrate_free(bench.inputs, bench.start, bench.stops,
                                          bench.settings(rtol, atol),
                                          Trajectory(bench.t, y_out, v_out), stats)
        wall = time.perf_counter() - start
        tip = y_out @ watch
    return Run(tip, wall, int(stats[radau.RHS_CALLS]), status == radau.SUCCESS)


def python_rhs(problem: tuple) -> Callable:
    """``first_order_rhs`` for ``problem`` with every jitted function replaced by its source."""
    from hubbeam.simulation.reference import pure_python

    fun = pure_python(first_order_rhs)
    fun.__globals__["problem_rhs"] = pure_python(radau.registered_rhs(type(problem)))
    return fun


def run_scipy(bench: BenchmarkCase, method: Method, rtol: float, atol: float,
              cap: float | None = None) -> Run:
    """``solve_ivp`` over the case, split at the end of the maneuver; ``cap`` (s) aborts the run
    with :class:`RunTooLong` (the check wraps the right-hand side, checked every 256 calls)."""
    fun = python_rhs(bench.problem) if method.python_rhs else first_order_rhs
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

