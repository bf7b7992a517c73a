"""Jitted hub maneuvers: Section 4's Eqs. (43)-(44) and tabulated or feedback-driven hubs.

A maneuver is an integer ``kind`` and a float array ``mp`` of its parameters (tables packed into
it by ``hubbeam.model.maneuvers``). The hub is *prescribed* (``PRESCRIBED``, ``SPEED_TABLE``: theta and
its rates are known functions of time, the torque that drives them is an output) or *free*
(``TORQUE``, ``TORQUE_TABLE``, ``PD``, ``STATE_FEEDBACK``, ``HELD``: the applied torque enters the
hub row of Eq. 24, or, with a drive, the command from which the drive makes it).

``PRESCRIBED``: the spin-up of Eq. (43) with the factor ``t`` the transcription lost (reproduction
note 1); ``mp = [wf, tf]``. The hub angle, rate and acceleration are

    theta_dot  = wf/tf * t - wf/(2 pi) * sin(2 pi t / tf)             (0 <= t <= tf)
    theta      = wf/(2 tf) * t^2 + wf tf/(4 pi^2) * (cos(2 pi t / tf) - 1)
    theta_ddot = wf/tf * (1 - cos(2 pi t / tf))

and theta_dot = wf, theta_ddot = 0 afterwards.

``TORQUE``: the rest-to-rest torque pulse of Eq. (44) with ``T = tf`` (note 8); ``mp = [tau_max, tf]``:
tau = tau_max sin(2 pi t / tf) for 0 <= t <= tf and zero afterwards; the hub is free.

``SPEED_TABLE``: theta_dot from a table ``(t_k, w_k)``; ``mp`` is a packed table (below) of the
clamped cubic spline of the speed (zero slope at both ends), theta its exact integral from
``theta(0) = 0`` and theta_ddot its derivative, continuous everywhere. Before the first time the
first speed is held, after the last time the last speed (theta_ddot = 0 outside the table).

``TORQUE_TABLE``: the applied torque interpolated linearly in a table ``(t_k, tau_k)``; the first
value is held before the table, the last after it; the hub is free.

``PD``: a free hub under the feedback torque ``tau = kp (theta_r - theta) + kd (theta_r' -
theta')``; ``mp = [kp, kd, reference kind, reference parameters...]`` with the reference
``PRESCRIBED`` (Eq. 43, ``[wf, tf]``; theta_r, theta_r' from :func:`hub_motion`) or ``ANGLE_TABLE``
(a packed clamped cubic spline of the angle, zero slope at both ends, held outside the table).

``STATE_FEEDBACK``: a free hub under ``tau = J theta_r'' + c theta_r' - K (x - x_r)`` with ``x =
(y, y')`` the whole state in the coordinates ``y = (theta, q1, q2)`` (size ``N = 1 + 2 n``; with a
compliant root ``(theta, q1, q2, phi)``, ``N = 2 + 2 n``, the hub angle ``phi`` referenced like
``theta``) and the reference ``x_r = (theta_r, theta_r'^2 s, 0, theta_r', 0, 0)``: the rigid
reference motion for the hub, the centrifugal stretch ``q1s = theta_r'^2 s`` for ``q1`` and zero for
``q2``. ``mp = [N, J, c, K (2 N gains: positions then rates), s (n), reference kind, reference
parameters...]`` with the reference as for ``PD`` (``J = c = 0``: no feedforward; ``J`` needs the
reference's acceleration, which only ``PRESCRIBED`` gives; ``c``, a drive's damping over its gain,
keeps a driven hub at the reference speed; with a drive the law gives volts). The torque may be
evaluated on the free coordinates of a model that integrates no ``q1`` (SFOAM, Eq. 40): the ``q1``
entries of ``K`` are then skipped (they are zero for such a model). ``PD`` is the case ``K = (kp,
0.., kd, 0..)``, ``J = 0``.

``HELD``: a free hub under a zero-order hold, the input a sampled controller writes as it runs
(``hubbeam.core.sampled``); ``mp = [c, s_0..s_{m-1}, u_0..u_{m-1}]`` holds ``c <= m`` switches,
``u_i`` from ``s_i`` (non-decreasing) to the next switch, right-continuous (at a switch, its new
value), ``u_0`` also before ``s_0`` and ``u_{c-1}`` after ``s_{c-1}``.

Packed table at offset ``o`` of ``mp`` (``m >= 2`` rows, times ``t_k`` increasing): ``mp[o] = m``,
then ``t_0..t_{m-1}``, the integrals ``I_k`` of the interpolant from 0 to ``t_k``, the cubic
coefficients ``c0..c3`` of every interval (value ``c0 + c1 s + c2 s^2 + c3 s^3``, ``s = t - t_k``),
and the last value; ``6 m - 2`` numbers. :func:`table` evaluates it without allocating.
"""

import math

from hubbeam.core.jit import borrowing_kernel

PRESCRIBED = 0
TORQUE = 1
SPEED_TABLE = 2
TORQUE_TABLE = 3
PD = 4
#: reference kind of a ``PD`` maneuver besides ``PRESCRIBED``
ANGLE_TABLE = 5
#: offset of the reference's parameters in a ``PD`` maneuver's ``mp``
PD_REFERENCE = 3
STATE_FEEDBACK = 6
#: offset of the gains in a ``STATE_FEEDBACK`` maneuver's ``mp``
FEEDBACK_GAINS = 3
HELD = 7


@borrowing_kernel
def prescribed(kind):
    """True if ``kind`` prescribes the hub motion (theta not integrated)."""
    return kind == PRESCRIBED or kind == SPEED_TABLE


@borrowing_kernel
def _spin_up(t, wf, tf):
    """Hub angle, rate and acceleration of Eq. (43)."""
    if t <= 0.0:
        return 0.0, 0.0, 0.0
    if t >= tf:
        return 0.5 * wf * tf + wf * (t - tf), wf, 0.0
    phase = 2.0 * math.pi * t / tf
    theta = 0.5 * wf / tf * t * t + wf * tf / (4.0 * math.pi ** 2) * (math.cos(phase) - 1.0)
    theta_dot = wf / tf * t - wf / (2.0 * math.pi) * math.sin(phase)
    theta_ddot = wf / tf * (1.0 - math.cos(phase))
    return theta, theta_dot, theta_ddot


@borrowing_kernel
def hub_motion(t, mp):
    """Prescribed hub angle, rate and acceleration of Eq. (43) at time ``t`` (``mp = [wf, tf]``)."""
    return _spin_up(t, mp[0], mp[1])


@borrowing_kernel
def applied_torque(t, mp):
    """Hub torque of Eq. (44) at time ``t`` (zero outside the pulse)."""
    tau_max = mp[0]
    tf = mp[1]
    if t <= 0.0 or t >= tf:
        return 0.0
    return tau_max * math.sin(2.0 * math.pi * t / tf)


@borrowing_kernel
def _interval(t, mp, ts, m):
    """The index ``lo`` with ``mp[ts + lo] <= t < mp[ts + lo + 1]`` among the ``m`` increasing
    times at ``mp[ts]`` (``mp[ts] <= t < mp[ts + m - 1]``), by bisection."""
    lo = 0
    hi = m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if mp[ts + mid] <= t:
            lo = mid
        else:
            hi = mid
    return lo


@borrowing_kernel
def table(t, mp, o):
    """``(integral from 0, value, derivative)`` at ``t`` of the table packed at ``mp[o]``."""
    m = int(mp[o])
    ts = o + 1
    integrals = ts + m
    cs = integrals + m
    if t < mp[ts]:
        y0 = mp[cs]
        return mp[integrals] + y0 * (t - mp[ts]), y0, 0.0
    if t >= mp[ts + m - 1]:
        y1 = mp[cs + 4 * (m - 1)]
        return mp[integrals + m - 1] + y1 * (t - mp[ts + m - 1]), y1, 0.0
    lo = _interval(t, mp, ts, m)
    s = t - mp[ts + lo]
    c = cs + 4 * lo
    c0 = mp[c]
    c1 = mp[c + 1]
    c2 = mp[c + 2]
    c3 = mp[c + 3]
    value = c0 + s * (c1 + s * (c2 + s * c3))
    derivative = c1 + s * (2.0 * c2 + s * 3.0 * c3)
    integral = mp[integrals + lo] + s * (c0 + s * (0.5 * c1 + s * (c2 / 3.0 + s * 0.25 * c3)))
    return integral, value, derivative


@borrowing_kernel
def prescribed_motion(kind, t, mp):
    """Hub angle, rate and acceleration of a prescribed maneuver (Eq. 43 or a speed table)."""
    if kind == SPEED_TABLE:
        return table(t, mp, 0)
    return hub_motion(t, mp)


@borrowing_kernel
def tracks_reference(kind):
    """True if ``kind`` is a controller tracking a reference motion (``PD``, ``STATE_FEEDBACK``)."""
    return kind == PD or kind == STATE_FEEDBACK


@borrowing_kernel
def reference_offset(kind, mp):
    """Offset in ``mp`` of the reference parameters of a ``PD`` or ``STATE_FEEDBACK`` maneuver
    (its reference kind sits just before them)."""
    if kind == PD:
        return PD_REFERENCE
    N = int(mp[0])
    return FEEDBACK_GAINS + 2 * N + (N - 1) // 2 + 1  # after the gains, the stretch and the kind


@borrowing_kernel
def feedback_torque(reference, y, v, mp, hub):
    """``tau = J theta_r'' - K (x - x_r)`` of a ``STATE_FEEDBACK`` maneuver at ``(y, y')`` (the
    full coordinates, or those of a model without ``q1``; module docstring) towards the
    ``reference`` ``(theta_r, theta_r', theta_r'')`` (:func:`reference_motion`). ``hub`` is where
    the hub angle of a compliant root sits in ``y`` (``hubbeam.core.root``; the last coordinate,
    which follows the reference motion like ``theta``), 0 without one."""
    N = int(mp[0])
    n = (N - 1) // 2
    k = FEEDBACK_GAINS
    s = k + 2 * N
    theta_r, theta_r_dot, theta_r_ddot = reference
    tau = 0.0
    if mp[1] != 0.0:
        tau = mp[1] * theta_r_ddot
    if mp[2] != 0.0:
        tau += mp[2] * theta_r_dot
    tau -= mp[k] * (y[0] - theta_r) + mp[k + N] * (v[0] - theta_r_dot)
    skip = N - y.shape[0]
    stretch = theta_r_dot * theta_r_dot
    for i in range(1, y.shape[0]):
        j = i + skip
        if i == hub:
            tau -= mp[k + j] * (y[i] - theta_r) + mp[k + N + j] * (v[i] - theta_r_dot)
            continue
        target = stretch * mp[s + j - 1] if j <= n else 0.0
        tau -= mp[k + j] * (y[i] - target) + mp[k + N + j] * v[i]
    return tau


@borrowing_kernel
def held_input(t, mp):
    """The value a ``HELD`` maneuver holds at ``t``: that of its last switch at or before ``t``
    (the first value before the first switch); see the module docstring."""
    count = int(mp[0])
    cap = (mp.shape[0] - 1) // 2
    values = 1 + cap
    if t >= mp[count]:  # the integrator asks beyond the last switch
        return mp[values + count - 1]
    if t < mp[1]:
        return mp[values]
    return mp[values + _interval(t, mp, 1, count)]


@borrowing_kernel
def table_motion(t, mp, o):
    """Value, derivative and second derivative at ``t`` of the table packed at ``mp[o]`` (zero
    rates where a value is held, before and after the table)."""
    m = int(mp[o])
    ts = o + 1
    cs = ts + 2 * m
    if t < mp[ts]:
        return mp[cs], 0.0, 0.0
    if t >= mp[ts + m - 1]:
        return mp[cs + 4 * (m - 1)], 0.0, 0.0
    lo = _interval(t, mp, ts, m)
    s = t - mp[ts + lo]
    c = cs + 4 * lo
    c1 = mp[c + 1]
    c2 = mp[c + 2]
    c3 = mp[c + 3]
    value = mp[c] + s * (c1 + s * (c2 + s * c3))
    return value, c1 + s * (2.0 * c2 + s * 3.0 * c3), 2.0 * c2 + 6.0 * c3 * s


@borrowing_kernel
def reference_motion(t, mp, o):
    """``(theta_r, theta_r', theta_r'')`` at ``t`` of the reference of a ``PD``-like maneuver whose
    parameters start at ``mp[o]`` (its kind, ``PRESCRIBED`` or ``ANGLE_TABLE``, at ``mp[o - 1]``):
    Eq. (43) or the clamped cubic spline of an angle table."""
    if int(mp[o - 1]) == ANGLE_TABLE:
        return table_motion(t, mp, o)
    return _spin_up(t, mp[o], mp[o + 1])


@borrowing_kernel
def tracking_torque(kind, reference, y, v, mp, hub):
    """Torque of a ``PD`` or ``STATE_FEEDBACK`` controller in the state ``(y, y')`` towards the
    ``reference`` ``(theta_r, theta_r', theta_r'')``; ``PD`` reads the hub angle and rate at
    ``y[hub]``, ``v[hub]`` (0, or the hub angle of a compliant root, ``hubbeam.core.root``)."""
    if kind == PD:
        return mp[0] * (reference[0] - y[hub]) + mp[1] * (reference[1] - v[hub])
    return feedback_torque(reference, y, v, mp, hub)


@borrowing_kernel
def open_loop_torque(kind, t, mp):
    """The command of a free hub that no controller closes at ``t``: Eq. (44), a torque table or a
    sampled controller's held input (with a drive, volts, ``hubbeam.core.drive``). A controller's
    command is its law towards its reference (:func:`tracking_torque`,
    ``hubbeam.core.shaping.shaped_torque``)."""
    if kind == HELD:
        return held_input(t, mp)
    if kind == TORQUE_TABLE:
        return table(t, mp, 0)[1]
    return applied_torque(t, mp)
