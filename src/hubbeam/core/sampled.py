"""A sampled digital controller around the hub, the whole run in one compiled call.

The plant is the hub-beam of :mod:`hubbeam.core.integrate` under a ``HELD`` maneuver
(:mod:`hubbeam.core.maneuver`): a zero-order hold whose switches the controller appends as it runs,
through the hub's drive if it has one (:mod:`hubbeam.core.drive`). The controller is a
:class:`~hubbeam.core.inputs.LoopArrays` and runs in the hooks of the integrator
(:func:`hubbeam.core.radau.register_hooks`) on :data:`SampledProblem`, the plant's problem with the
loop and its work arrays: the stops of the integration are the sample times ``t_k = k Ts`` and
the times ``(k + D) Ts`` at which the commands reach the plant, so no step crosses an input
switch and the state is known at every sample.

At each sample ``t_k`` (``docs/sampled-control.md``, the convention this module implements):

1. sensors ``s_j = gain_j (c_j . x) + offset_j`` (``c_j`` on the integrated coordinates and rates),
   the value of the analog low-pass where the sensor has one, plus ``sigma_j w_jk``, then the
   quantisation: ``ROUND``, ``quantum round(s / quantum)`` (rounding half up; error at most half a
   quantum), or ``EDGES``, ``quantum floor(s / quantum)`` (an incremental encoder counting the edges
   passed since a zero on an edge; error in ``[0, quantum)``): the measurement ``m_k``;
2. the reference ``rho_k = (theta_r, theta_r', theta_r'')`` (:func:`~hubbeam.core.maneuver.reference_motion`);
3. ``e_k = m_k - R_m rho_k``, ``xhat_k = E xc_k + F e_k``, ``u_cmd_k = U_r . rho_k - K . xhat_k``,
   ``u_k = clip(u_cmd_k, -u_max, u_max)``, ``xc_{k+1} = Ac xc_k + Bc e_k + Bu (u_k - U_r . rho_k)``;
4. ``u_k`` is queued and reaches the plant at ``(k + D) Ts``, where the integrator restarts.

A sample is processed before a switch at the same time, so that with ``D = 0`` the command of
``t_k`` acts from ``t_k`` on.

The analog low-pass ``tau s_f' = s - s_f`` is discretised exactly on the dense output: on every
accepted step ``[t0, t0 + h]`` the sensor signal is the polynomial of degree 5 in ``sigma = (t -
t0) / h`` that the integrator's quintic Hermite output gives (positions; the rates are its
derivative), and

    s_f(t0 + h) = exp(-r) s_f(t0) + sum_k a_k J_k(r),    J_k(r) = r int_0^1 exp(-r (1 - sigma)) sigma^k dsigma,

``r = h / tau``, ``a_k`` the polynomial's coefficients (:func:`lowpass_weights` gives the ``J_k``
to rounding error for every ``r``). The filter's only error is then that of the dense output,
which a first-order low-pass of unit gain does not amplify. The filter starts in equilibrium,
``s_f(0) = s(0)``.
"""

import math
from collections import namedtuple

import numpy as np

from hubbeam.core.cfoam_rhs import cfoam_problem
from hubbeam.core.foam_rhs import foam_problem
from hubbeam.core.inputs import FAMILIES, family
from hubbeam.core.integrate import _fill_rows_cfoam, _fill_rows_foam, _states
from hubbeam.core.jit import borrowing_kernel, kernel
from hubbeam.core.radau import HERMITE, problem_rhs, register_hooks, register_rhs
from hubbeam.core.shaping import shaped_reference_motion

#: quantisation modes of a sensor (``LoopSensors.mode``)
ROUND = 0
EDGES = 1
#: ``r = h / tau`` above which :func:`lowpass_weights` recurs upwards (below: the power series)
RECURRENCE_FROM = 2.0

#: The work arrays of a running loop: the controller state ``xc`` and its update ``xc_next``, the
#: deviations ``error`` (p), the reference ``rho`` (3), the low-pass outputs ``filtered`` (p), a
#: step's signal polynomial ``poly`` and filter weights ``weights`` (6 each), and ``counters``:
#: the next sample and the next switch.
LoopWork = namedtuple("LoopWork", "xc xc_next error rho filtered poly weights counters")

#: A radau5 problem: the plant's problem (``FoamProblem`` or ``CfoamProblem`` under a ``HELD``
#: maneuver), the :class:`~hubbeam.core.inputs.LoopArrays` ``loop`` and its :data:`LoopWork`.
SampledProblem = namedtuple("SampledProblem", "plant loop work")


@kernel
def loop_work(loop):
    """The :data:`LoopWork` of ``loop`` at the start (``xc = xc0``)."""
    p = loop.sensors.gain.shape[0]
    nc = loop.matrices.Ac.shape[0]
    return LoopWork(loop.matrices.xc0.copy(), np.empty(nc), np.empty(p), np.empty(3), np.empty(p),
                    np.empty(6), np.empty(6), np.zeros(2, np.int64))


@borrowing_kernel
def sampled_rhs(t, y, v, a, problem):
    """The plant's accelerations: its input is the held value the loop last switched to."""
    problem_rhs(t, y, v, a, problem.plant)


@borrowing_kernel
def sensor_value(sensors, j, y, v):
    """``gain_j (c_j . (y, v)) + offset_j``: sensor ``j`` before its low-pass, noise and
    quantisation."""
    row = sensors.rows[j]
    nf = y.shape[0]
    s = 0.0
    for m in range(nf):
        s += row[m] * y[m] + row[nf + m] * v[m]
    return sensors.gain[j] * s + sensors.offset[j]


@borrowing_kernel
def quantised(value, quantum, mode):
    """``value`` on the grid of ``quantum`` (0: unchanged): rounded (``ROUND``) or counted down to
    the edge below (``EDGES``)."""
    if quantum <= 0.0:
        return value
    if mode == EDGES:
        return quantum * math.floor(value / quantum)
    return quantum * math.floor(value / quantum + 0.5)


@borrowing_kernel
def lowpass_weights(r, weights):
    """``weights[k] = J_k(r) = r int_0^1 exp(-r (1 - s)) s^k ds``, ``k = 0..5`` (module docstring).

    Above :data:`RECURRENCE_FROM` by the upward recurrence ``J_0 = 1 - exp(-r)``, ``J_k = 1 - (k / r)
    J_(k-1)`` (integration by parts), which multiplies a rounding error by ``k / r < 5 / 2`` per
    step; below, by the alternating series ``J_k = r sum_i (-r)^i k! / (i + k + 1)!``, whose terms
    do not exceed the first there (no cancellation) and fall below rounding error in 30 terms."""
    if r > RECURRENCE_FROM:
        J = -math.expm1(-r)
        weights[0] = J
        for k in range(1, weights.shape[0]):
            J = 1.0 - k / r * J
            weights[k] = J
        return
    for k in range(weights.shape[0]):
        term = r / (k + 1)
        total = term
        for i in range(1, 40):
            term *= -r / (i + k + 1)
            total += term
            if abs(term) <= 1e-17 * abs(total):
                break
        weights[k] = total


@borrowing_kernel
def signal_polynomial(sensors, j, h, start, end, poly):
    """The coefficients ``poly[k]`` of ``sigma^k`` of sensor ``j`` (before its low-pass) along a
    step of size ``h`` from ``start = (y0, v0, a0)`` to ``end = (y1, v1, a1)``: the quintic Hermite
    positions of the dense output (``radau.HERMITE``) and their time derivative, the rates."""
    y0, v0, a0 = start
    y1, v1, a1 = end
    row = sensors.rows[j]
    nf = y0.shape[0]
    h2 = h * h
    p0 = p1 = p2 = p3 = p4 = p5 = 0.0  # position part of the row on the Hermite data
    r0 = r1 = r2 = r3 = r4 = r5 = 0.0  # rate part
    for m in range(nf):
        cy = row[m]
        cv = row[nf + m]
        p0 += cy * y0[m]
        p1 += cy * v0[m]
        p2 += cy * a0[m]
        p3 += cy * y1[m]
        p4 += cy * v1[m]
        p5 += cy * a1[m]
        r0 += cv * y0[m]
        r1 += cv * v0[m]
        r2 += cv * a0[m]
        r3 += cv * y1[m]
        r4 += cv * v1[m]
        r5 += cv * a1[m]
    p1 *= h
    p4 *= h
    p2 *= h2
    p5 *= h2
    r1 *= h
    r4 *= h
    r2 *= h2
    r5 *= h2
    H = HERMITE
    for k in range(6):
        c = H[0, k] * p0 + H[1, k] * p1 + H[2, k] * p2 + H[3, k] * p3 + H[4, k] * p4 + H[5, k] * p5
        if k < 5:
            c += (k + 1) * (H[0, k + 1] * r0 + H[1, k + 1] * r1 + H[2, k + 1] * r2
                            + H[3, k + 1] * r3 + H[4, k + 1] * r4 + H[5, k + 1] * r5) / h
        poly[k] = sensors.gain[j] * c
    poly[0] += sensors.offset[j]


@borrowing_kernel
def sampled_after_step(t, h, start, end, problem):
    """Advance every sensor's analog low-pass over the accepted step (module docstring)."""
    sensors = problem.loop.sensors
    work = problem.work
    for j in range(sensors.tau.shape[0]):
        tau = sensors.tau[j]
        if tau > 0.0:
            signal_polynomial(sensors, j, h, start, end, work.poly)
            r = h / tau
            lowpass_weights(r, work.weights)
            f = math.exp(-r) * work.filtered[j]
            for k in range(6):
                f += work.poly[k] * work.weights[k]
            work.filtered[j] = f


@borrowing_kernel
def take_sample(k, y, v, problem):
    """Sample ``k`` at ``t_k`` in the state ``(y, v)`` of the integrated coordinates: measure,
    estimate, compute the command, update the controller, record (module docstring)."""
    loop = problem.loop
    work = problem.work
    sensors = loop.sensors
    M = loop.matrices
    records = loop.records
    t = loop.timing.sample_times[k]
    records.t[k] = t
    rho = work.rho
    rho[0], rho[1], rho[2] = shaped_reference_motion(t, loop.reference, 1, loop.shaper)
    error = work.error
    for j in range(error.shape[0]):
        s = work.filtered[j] if sensors.tau[j] > 0.0 else sensor_value(sensors, j, y, v)
        records.sensed[k, j] = s
        m = quantised(s + sensors.sigma[j] * sensors.noise[k, j], sensors.quantum[j], sensors.mode[j])
        records.measured[k, j] = m
        error[j] = m - (M.R_m[j, 0] * rho[0] + M.R_m[j, 1] * rho[1] + M.R_m[j, 2] * rho[2])
    xc = work.xc
    nc = xc.shape[0]
    feedforward = M.U_r[0] * rho[0] + M.U_r[1] * rho[1] + M.U_r[2] * rho[2]
    command = feedforward
    for i in range(M.K.shape[0]):
        x = 0.0
        for c in range(nc):
            x += M.E[i, c] * xc[c]
        for j in range(error.shape[0]):
            x += M.F[i, j] * error[j]
        records.estimate[k, i] = x
        command -= M.K[i] * x
    u_max = loop.timing.u_max
    u = min(max(command, -u_max), u_max)
    records.command[k] = command
    records.applied[k] = u
    for i in range(nc):
        x = M.Bu[i] * (u - feedforward)
        for c in range(nc):
            x += M.Ac[i, c] * xc[c]
        for j in range(error.shape[0]):
            x += M.Bc[i, j] * error[j]
        work.xc_next[i] = x
    for i in range(nc):
        xc[i] = work.xc_next[i]


@borrowing_kernel
def hold(mp, t, value):
    """Append the switch ``(t, value)`` to the ``HELD`` maneuver's table ``mp``."""
    count = int(mp[0])
    cap = (mp.shape[0] - 1) // 2
    mp[1 + count] = t
    mp[1 + cap + count] = value
    mp[0] = count + 1


@borrowing_kernel
def sampled_at_stop(t, y, v, problem):
    """At a stop (or the start) ``t``: take the samples due by ``t``, then switch the plant's input
    to every command due by ``t``; True if it switched."""
    loop = problem.loop
    work = problem.work
    timing = loop.timing
    counters = work.counters
    k = counters[0]
    while k < timing.sample_times.shape[0] and timing.sample_times[k] <= t:
        if k == 0:  # the analog low-passes start in equilibrium
            for j in range(work.filtered.shape[0]):
                work.filtered[j] = sensor_value(loop.sensors, j, y, v)
        take_sample(k, y, v, problem)
        k += 1
    counters[0] = k
    i = counters[1]
    switched = False
    while i < k and timing.switch_times[i] <= t:
        hold(problem.plant.mp, timing.switch_times[i], loop.records.applied[i])
        i += 1
        switched = True
    counters[1] = i
    return switched


register_rhs(SampledProblem, sampled_rhs)
register_hooks(SampledProblem, sampled_at_stop, sampled_after_step)


@kernel
def simulate_sampled_foam_family(inputs, start, t_out, t_stops, settings, loop, out, stats):
    """:func:`simulate_sampled_kernel` of TLAM, FOAM and SFOAM (``FoamProblem``)."""
    plant = foam_problem(inputs)
    problem = SampledProblem(plant, loop, loop_work(loop))
    status, t_stop, free, states = _states(problem, inputs, start, t_out, t_stops, settings, stats)
    _fill_rows_foam(plant, inputs, free, states, out)
    return status, t_stop


@kernel
def simulate_sampled_cfoam_family(inputs, start, t_out, t_stops, settings, loop, out, stats):
    """:func:`simulate_sampled_kernel` of CFOAM (``CfoamProblem``)."""
    plant = cfoam_problem(inputs)
    problem = SampledProblem(plant, loop, loop_work(loop))
    status, t_stop, free, states = _states(problem, inputs, start, t_out, t_stops, settings, stats)
    _fill_rows_cfoam(plant.ct, inputs, free, states, out)
    return status, t_stop


#: the compiled sampled-loop kernel of each family of models (``inputs.FAMILIES``)
SAMPLED_KERNELS = dict(zip(FAMILIES, (simulate_sampled_foam_family, simulate_sampled_cfoam_family)))


def simulate_sampled_kernel(inputs, start, t_out, t_stops, settings, loop, out, stats):
    """Simulate the hub-beam under the sampled controller ``loop`` and fill ``out``, in one
    compiled call (as :func:`hubbeam.core.integrate.simulate_kernel`, whose arguments these are).

    ``inputs.kind`` is ``HELD`` and ``inputs.mp`` its table with room for every switch, holding
    the input before the first command (``u_init``); the loop appends the switches as it runs, and
    the outputs read them back. ``t_stops`` holds the sample and switch times of
    ``loop.timing`` inside the output span. ``loop`` (:class:`~hubbeam.core.inputs.LoopArrays`)
    receives its records (every sample taken up to the stop of the run). Returns radau5's
    ``(status, t_stop)``.
    """
    return SAMPLED_KERNELS[family(inputs.traits)](inputs, start, t_out, t_stops, settings, loop, out,
                                                  stats)
