"""Slow, independent reference solutions with scipy's ``solve_ivp``.

The same equations of motion (``hubbeam.core.eom.accelerations``), written as the first-order
system ``z = (y_free, v_free)``, are integrated by one of scipy's general-purpose integrators at a
tight tolerance and sampled on the simulation's output grid; the outputs are then evaluated as in
:func:`hubbeam.simulation.simulate.simulate`. This checks the fast path's time integration (Radau IIA kernel,
step-size control, dense output, and its right-hand sides ``core.foam_rhs`` and
``core.cfoam_rhs``) against code that shares nothing with it but the model: the general
mass-matrix equations with CFOAM's point-cloud sum.

By default the accelerations are evaluated in plain Python: :func:`pure_python` rebuilds a jitted
function from its source with every jitted function it calls replaced by its plain-Python
version, so no numba-compiled code runs inside the right-hand side. That is slow (about 0.1-1 ms
per call); ``pure_python=False`` calls the jitted kernel instead.
"""

from __future__ import annotations

import time
import types
from collections.abc import Mapping

import numpy as np
import xarray as xr
from numba.core.dispatcher import Dispatcher
from scipy.integrate import solve_ivp

from hubbeam.configuration.settings import Case, Numerics, simulation_settings
from hubbeam.core import eom
from hubbeam.core.inputs import IDENTITY_SHAPER, NO_DRIVE, SimulationInputs, Trajectory
from hubbeam.core.integrate import fill_outputs, n_output_columns
from hubbeam.core.radau import LEFT_RANGE, NON_FINITE, STEP_UNDERFLOW, SUCCESS
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import SystemMatrices
from hubbeam.model.models import model
from hubbeam.model.parameters import BeamParameters
from hubbeam.model.root import joint_inputs
from hubbeam.model.shapers import Shaper
from hubbeam.simulation.simulate import (
    Resolved,
    Run,
    build_dataset,
    case_matrices,
    initial_state,
    output_times,
    step_stops,
)

#: scipy methods accepted for the reference (implicit ones cope with the stiff axial modes)
METHODS = ("Radau", "BDF", "LSODA", "DOP853", "RK45")


def pure_python(func, _done=None):
    """The plain-Python version of the jitted ``func``, calling plain-Python versions throughout.

    Each jitted global that ``func`` (recursively) calls is replaced, in a copy of the function's
    globals, by its own plain-Python version; functions that are not jitted are returned as is.
    """
    done = {} if _done is None else _done
    if not isinstance(func, Dispatcher):
        return func
    if func in done:
        return done[func]
    source = func.py_func
    namespace = dict(source.__globals__)
    clone = types.FunctionType(source.__code__, namespace, source.__name__, source.__defaults__,
                               source.__closure__)
    done[func] = clone
    for name, value in source.__globals__.items():
        if isinstance(value, Dispatcher):
            namespace[name] = pure_python(value, done)
    return clone


def reference_simulation(case: Case | Mapping, params: BeamParameters, numerics: Numerics | Mapping,
                         matrices: SystemMatrices | None = None, *, method: str = "Radau",
                         rtol: float = 1e-12, atol: float = 1e-14,
                         pure_python_rhs: bool = True, shaper: Shaper | None = None) -> xr.Dataset:
    """The simulation dataset of ``case`` computed with ``scipy.integrate.solve_ivp``.

    Arguments as :func:`hubbeam.simulation.simulate.simulate` (``numerics`` gives the output grid and the
    divergence limit); ``method``, ``rtol``, ``atol`` configure ``solve_ivp`` (``atol`` applies to
    every free position and velocity). The run is split at the end of the maneuver, as in the fast
    path (and at every row of a maneuver's table). Integrator attributes name scipy, the method and
    its counts (``n_steps`` is not known to scipy and is omitted; ``n_rhs`` is scipy's ``nfev``).
    The run starts from the case's initial state (:func:`hubbeam.simulation.simulate.initial_state`);
    ``shaper`` shapes the maneuver's command, as in
    :func:`hubbeam.simulation.simulate.simulate`.
    """
    case, numerics = simulation_settings(case, numerics, params.L)
    if method not in METHODS:
        raise ValueError(f"method = {method!r}; allowed: one of {', '.join(METHODS)}")
    sm = case_matrices(case, params, numerics, matrices)
    kind, mp = case.maneuver.kernel_parameters()
    link, root = joint_inputs(sm, case.root_spring)
    inputs = SimulationInputs(model(case.model).traits, kind, mp, damping_matrices(case.damping, sm), link,
                              NO_DRIVE if case.drive is None else case.drive.packed(),
                              IDENTITY_SHAPER if shaper is None else shaper.kernel_array(), root)
    n = case.modes
    joint = case.root_spring is not None
    free = eom.free_coordinates(inputs)
    nf = free.size
    accelerations = pure_python(eom.accelerations) if pure_python_rhs else eom.accelerations
    y = np.zeros(eom.coordinate_count(inputs))
    v = np.zeros_like(y)
    a = np.zeros_like(y)
    watched = np.isin(free, np.arange(1 + n, 1 + 2 * n))  # the q2 among the free coordinates

    def rhs(t, z):
        y[free] = z[:nf]
        v[free] = z[nf:]
        accelerations(inputs, t, y, v, free, a)
        return np.concatenate([z[nf:], a[free]])

    tip_limit = float(numerics.divergence_limit) * params.L

    def tip_event(t, z):
        return tip_limit - abs(sm.f2L @ z[:nf][watched])

    tip_event.terminal = True

    t = output_times(case.t_end, numerics.output_step)
    edges = [t[0], *step_stops(case.maneuver, t, shaper), t[-1]]
    start = initial_state(case, sm)
    z = np.concatenate([start.y[free], start.v[free]])
    states = np.full((t.size, 2 * nf), np.nan)
    status, t_stop, nfev, njev, nlu = SUCCESS, t[-1], 0, 0, 0
    start = time.perf_counter()
    for t0, t1 in zip(edges[:-1], edges[1:]):
        inside = (t >= t0) & (t <= t1)
        grid = t[inside]
        # the state at t1 starts the next piece: evaluate it there too when t1 is off the grid
        evaluate = grid if grid.size and grid[-1] == t1 else np.append(grid, t1)
        result = solve_ivp(rhs, (t0, t1), z, method=method, t_eval=evaluate, rtol=rtol,
                           atol=atol, events=tip_event)
        nfev += result.nfev
        njev += result.njev
        nlu += result.nlu
        count = min(result.t.size, grid.size)
        states[np.flatnonzero(inside)[:count]] = result.y.T[:count]
        if result.status == 1:
            status, t_stop = LEFT_RANGE, float(result.t_events[0][0])
            break
        if result.status != 0:
            finite = np.all(np.isfinite(result.y))
            status = STEP_UNDERFLOW if finite else NON_FINITE
            t_stop = float(result.t[-1]) if result.t.size else t0
            break
        z = result.y[:, -1]
    wall = time.perf_counter() - start
    out = np.empty((t.size, n_output_columns(n, joint)))
    fill_outputs(inputs, free, Trajectory(t, np.ascontiguousarray(states[:, :nf]),
                                          np.ascontiguousarray(states[:, nf:])), out)
    integrator = {"integrator": f"scipy.integrate.solve_ivp {method} (hubbeam.simulation.reference)",
                  "rtol": float(rtol), "atol": float(atol), "n_rhs": int(nfev),
                  "n_jacobian": int(njev), "n_lu": int(nlu), "wall_time_s": float(wall),
                  "pure_python_rhs": int(pure_python_rhs)}
    return build_dataset(case, params, numerics, sm, Run(t, out, status, t_stop, integrator),
                         Resolved(shaper=shaper))

