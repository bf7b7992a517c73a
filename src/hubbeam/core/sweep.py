"""Parameter sweeps in one parallel kernel: many simulations, only tip-deflection extrema kept.

Every point of a sweep is one simulation from rest, as in
:func:`hubbeam.core.integrate.simulate_kernel`: the same integration
(:func:`hubbeam.core.integrate.integrate_free`) and the same watch on the tip
deflection. Instead of every output of the simulation dataset, a point keeps
only what a map shows, formed from the dense output of the free coordinates on a coarse uniform
grid (plus the end of the maneuver ``t_mark``):

* ``peak``: max ``|v(L)|`` over ``[0, t_end]``, ``v(L) = f2(L) q2`` the transverse tip deflection;
* ``peak_time``: where it occurs;
* ``residual``: max ``|v(L)|`` over ``[t_mark, t_end]``, the residual vibration after the maneuver.

Between two grid times the tip deflection is the cubic Hermite polynomial through ``v(L)`` and its
rate at both ends (interpolation error ``O(dt^4)``; for the first bending mode, ``omega ~ 3 rad/s``,
and ``dt = 0.05 s`` about ``1e-6`` relative), whose extrema are found in closed form, so a
coarse grid does not clip the peaks.

The points run in parallel on threads: :func:`sweep_tip_extrema` runs one strided share of the
points (thread ``k`` of ``T`` takes points ``k, k + T, k + 2T, ...``, which balances the load as
neighbouring grid points cost about the same) and releases the GIL, so ``T`` Python threads run
``T`` shares at once (:func:`hubbeam.simulation.sweep.run_sweep`). This was chosen over a ``numba.prange``
loop (``parallel=True``), which caches as well but took about 10 s more to compile (measured,
README), a large part of the workflow's time budget. The per-point kernels are inlined into the
loop, which saves one more compilation of the integrator they call. A run that stops early
(left range, non-finite state, vanishing step, step budget) has NaN extrema; its status and stop
time are kept.
"""

import math
from typing import NamedTuple

import numba
import numpy as np

from hubbeam.core.eom import free_dofs
from hubbeam.core.inputs import ModelTraits, RootJoint, SimulationInputs, State, Trajectory
from hubbeam.core.integrate import integrate_free
from hubbeam.core.jit import JIT_OPTIONS, inline_kernel, kernel
from hubbeam.core.radau import STAT_NAMES, SUCCESS
from hubbeam.core.system_matrices import SystemMatrices

#: columns of the float result array of :func:`sweep_tip_extrema`
RESULT_COLUMNS = ("peak", "peak_time", "residual", "t_stop")
PEAK, PEAK_TIME, RESIDUAL, T_STOP = range(len(RESULT_COLUMNS))
N_STATS = len(STAT_NAMES)


class SweepPoints(NamedTuple):
    """The per-point inputs of a sweep (``P`` points): ``traits`` (P, 4) bool, the
    :class:`~hubbeam.core.inputs.ModelTraits` of each point's model as a row; the maneuver
    ``kind`` (one for the sweep) and parameters ``mp`` (P, ...); ``matrix_index`` (P,) into the
    stack of system matrices; the end time ``t_end`` and the start of the residual window
    ``t_mark`` (P,)."""

    traits: np.ndarray
    kind: int
    mp: np.ndarray
    matrix_index: np.ndarray
    t_end: np.ndarray
    t_mark: np.ndarray


class SweepResults(NamedTuple):
    """What a sweep writes per point: ``results`` (P, len(RESULT_COLUMNS)), the radau5
    ``status`` (P,) and counters ``stats`` (P, N_STATS)."""

    results: np.ndarray
    status: np.ndarray
    stats: np.ndarray


@kernel
def traits_at(rows, k):
    """The :class:`~hubbeam.core.inputs.ModelTraits` stored as row ``k`` of ``rows``."""
    return ModelTraits(rows[k, 0], rows[k, 1], rows[k, 2], rows[k, 3])


@kernel
def matrices_at(stack, k):
    """The :class:`~hubbeam.core.system_matrices.SystemMatrices` number ``k`` of a stack of them (every field
    with a leading axis, scalars as 1-D arrays); array fields are views."""
    return SystemMatrices(stack.Jh[k], stack.Jb[k], stack.K1[k], stack.K2[k], stack.M1[k],
                          stack.M2[k], stack.V1[k], stack.V2[k], stack.D[k], stack.R[k],
                          stack.rA[k], stack.x[k], stack.w[k], stack.F1[k], stack.F2[k],
                          stack.S[k], stack.f1L[k], stack.f2L[k], stack.SL[k], stack.Jt[k],
                          stack.dF2t[k])


@kernel
def output_grid(t_end, step, t_mark):
    """``0, step, 2 step, ...`` below ``t_end``, then ``t_end``; ``t_mark``, when inside
    ``(0, t_end)``, is inserted (or replaces the grid time it matches to 1e-9 steps)."""
    count = int(math.ceil(t_end / step - 1e-9))  # uniform times 0 .. (count - 1) step < t_end
    ratio = t_mark / step
    j_mark = int(round(ratio))
    inside = 0.0 < t_mark < t_end
    on_grid = abs(ratio - j_mark) <= 1e-9 and j_mark < count
    insert = 1 if inside and not on_grid else 0
    t = np.empty(count + 1 + insert)
    k = 0
    for i in range(count):
        ti = i * step
        if insert == 1 and k == i and ti > t_mark:
            t[k] = t_mark
            k += 1
        t[k] = ti
        k += 1
    if k == count and insert == 1:  # t_mark after the last uniform time
        t[k] = t_mark
        k += 1
    t[k] = t_end
    if inside and on_grid:
        t[j_mark] = t_mark
    return t


@kernel
def hermite_abs_max(p0, d0, p1, d1, h):
    """Max of ``|H(s)|``, ``s`` in ``[0, 1]``, for the cubic ``H`` with ``H(0) = p0``,
    ``H(1) = p1``, ``H'(0) = h d0``, ``H'(1) = h d1``; returns ``(value, s)``."""
    c = h * d0
    b = 3.0 * (p1 - p0) - h * (2.0 * d0 + d1)
    a = 2.0 * (p0 - p1) + h * (d0 + d1)
    best, s_best = abs(p0), 0.0
    if abs(p1) > best:
        best, s_best = abs(p1), 1.0
    # stationary points: 3 a s^2 + 2 b s + c = 0
    qa, qb, qc = 3.0 * a, 2.0 * b, c
    roots = np.empty(2)
    count = 0
    if qa == 0.0:
        if qb != 0.0:
            roots[0] = -qc / qb
            count = 1
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            # numerically stable pair of roots
            q = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))
            roots[0] = q / qa
            count = 1
            if q != 0.0:
                roots[1] = qc / q
                count = 2
    for i in range(count):
        s = roots[i]
        if 0.0 < s < 1.0:
            value = abs(((a * s + b) * s + c) * s + p0)
            if value > best:
                best, s_best = value, s
    return best, s_best


@inline_kernel
def tip_extrema(inputs, t_end, t_mark, output_step, settings, stats):
    """One sweep point: simulate the undamped :class:`~hubbeam.core.inputs.SimulationInputs`
    ``inputs`` from rest to ``t_end`` with the
    :class:`~hubbeam.core.inputs.IntegratorSettings` ``settings`` and return
    ``(status, t_stop, peak, peak_time, residual)`` (see the module docstring; NaN extrema unless
    the run succeeded). ``stats`` receives radau5's counters."""
    n = inputs.sm.K1.shape[0]
    nf = free_dofs(inputs.traits, inputs.kind, n).shape[0]
    t_out = output_grid(t_end, output_step, t_mark)
    n_out = t_out.shape[0]
    y_out = np.empty((n_out, nf))
    v_out = np.empty((n_out, nf))
    rest = State(np.zeros(1 + 2 * n), np.zeros(1 + 2 * n))
    status, t_stop, watch = integrate_free(inputs, rest, np.array([t_mark]), settings,
                                           Trajectory(t_out, y_out, v_out), stats)
    if status != SUCCESS:
        return status, t_stop, np.nan, np.nan, np.nan
    peak = 0.0
    residual = 0.0 if t_mark < t_end else np.nan
    peak_time = 0.0
    p0 = d0 = 0.0
    for i in range(nf):
        p0 += watch[i] * y_out[0, i]
        d0 += watch[i] * v_out[0, i]
    for k in range(n_out - 1):
        p1 = d1 = 0.0
        for i in range(nf):
            p1 += watch[i] * y_out[k + 1, i]
            d1 += watch[i] * v_out[k + 1, i]
        h = t_out[k + 1] - t_out[k]
        value, s = hermite_abs_max(p0, d0, p1, d1, h)
        if value > peak:
            peak, peak_time = value, t_out[k] + s * h
        if t_out[k] >= t_mark and value > residual:
            residual = value
        p0, d0 = p1, d1
    return status, t_stop, peak, peak_time, residual


@numba.njit(nogil=True, **JIT_OPTIONS)
def sweep_tip_extrema(first, stride, points, stack, output_step, settings, found):
    """Run the points ``first, first + stride, ...`` of a sweep: one thread's share.

    Point ``p`` of the :class:`SweepPoints` ``points`` simulates the model with traits
    ``traits_at(points.traits, p)`` under maneuver ``points.kind`` with parameters
    ``points.mp[p]``, system matrices ``matrices_at(stack, points.matrix_index[p])``, undamped,
    up to ``points.t_end[p]``, residual window from ``points.t_mark[p]``, with the integrator
    ``settings`` (:func:`tip_extrema`). Writes ``found.results[p]`` (columns
    :data:`RESULT_COLUMNS`), ``found.status[p]`` (radau5 status) and ``found.stats[p]`` (radau5
    counters) of the :class:`SweepResults` ``found``. The kernel releases the GIL, so that
    ``stride`` Python threads, each with its own ``first``, run a sweep on ``stride`` cores.
    """
    results = found.results
    n = stack.K1.shape[1]
    undamped = np.zeros((2, n, n))
    no_drive = np.zeros(0)
    unshaped = np.zeros((2, 1))  # the identity shaper (numba does not fill a NamedTuple's defaults)
    unshaped[1, 0] = 1.0
    rigid = RootJoint(np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 0)))  # the rigid root, NO_ROOT
    for p in range(first, points.traits.shape[0], stride):
        sm = matrices_at(stack, points.matrix_index[p])
        inputs = SimulationInputs(traits_at(points.traits, p), points.kind, points.mp[p], undamped,
                                  sm, no_drive, unshaped, rigid)
        code, t_stop, peak, peak_time, residual = tip_extrema(
            inputs, points.t_end[p], points.t_mark[p], output_step, settings, found.stats[p])
        found.status[p] = code
        results[p, PEAK] = peak
        results[p, PEAK_TIME] = peak_time
        results[p, RESIDUAL] = residual
        results[p, T_STOP] = t_stop
