"""Jitted shaped commands: a maneuver's command convolved with a sequence of impulses.

A command shaper (Singer & Seering 1990) is ``k`` impulses of amplitudes ``A_i`` (summing to 1)
at times ``t_i >= 0``; the kernels receive it as the array ``shaper`` of shape ``(2, k)``, times
in the first row and amplitudes in the second (``SimulationInputs.shaper``, built by
``hubbeam.model.shapers``). The shaped command is

    r_s(t) = sum_i A_i r(t - t_i),

with ``r`` at negative times the maneuver's own value before it starts (rest for Eqs. 43-44, the
held first row of a table). What ``r`` is depends on the maneuver (:mod:`hubbeam.core.maneuver`):

* a prescribed hub (Eq. 43, a speed table): the hub angle, rate and acceleration
  (:func:`shaped_motion`); a speed table that starts spinning at ``w0`` gives the angle
  ``-w0 sum_i A_i t_i`` at ``t = 0`` (the shaper's mean delay), which enters no equation;
* a free hub under a torque (Eq. 44, a torque table): the torque (:func:`shaped_torque`);
* a controller (``PD``, ``STATE_FEEDBACK``): its reference ``(theta_r, theta_r', theta_r'')``
  (:func:`shaped_reference`); the control law then acts on the shaped reference and the present
  state, so the feedback itself is not delayed.

The sum starts with the first impulse's product, ``A_0 r(t - t_0)``: the identity shaper (one
impulse of amplitude 1 at ``t = 0``, the default) then performs ``1 * r(t - 0)``, which is
``r(t)`` to the bit, and every unshaped run is unchanged.
"""

from hubbeam.core.jit import borrowing_kernel
from hubbeam.core.maneuver import (
    open_loop_torque,
    prescribed_motion,
    reference_motion,
    reference_offset,
    tracking_torque,
    tracks_reference,
)


@borrowing_kernel
def _command(kind, t, mp, o):
    """The command triple at ``t``: a prescribed hub's angle, rate and acceleration (``o < 0``),
    or a controller's reference whose parameters start at ``mp[o]``."""
    if o < 0:
        return prescribed_motion(kind, t, mp)
    return reference_motion(t, mp, o)


@borrowing_kernel
def _shaped_command(kind, t, mp, o, shaper):
    """``sum_i A_i`` times the command triple (:func:`_command`) at ``t - t_i``."""
    a = shaper[1, 0]
    first, second, third = _command(kind, t - shaper[0, 0], mp, o)
    first *= a
    second *= a
    third *= a
    for i in range(1, shaper.shape[1]):
        a = shaper[1, i]
        first_i, second_i, third_i = _command(kind, t - shaper[0, i], mp, o)
        first += a * first_i
        second += a * second_i
        third += a * third_i
    return first, second, third


@borrowing_kernel
def shaped_motion(kind, t, mp, shaper):
    """Shaped angle, rate and acceleration of a prescribed hub at ``t``: ``sum_i A_i
    prescribed_motion(kind, t - t_i, mp)``."""
    return _shaped_command(kind, t, mp, -1, shaper)


@borrowing_kernel
def shaped_reference(kind, t, mp, shaper):
    """Shaped reference ``(theta_r, theta_r', theta_r'')`` at ``t`` of a tracking maneuver
    (:func:`hubbeam.core.maneuver.reference_motion`)."""
    return _shaped_command(kind, t, mp, reference_offset(kind, mp), shaper)


@borrowing_kernel
def shaped_reference_motion(t, mp, o, shaper):
    """Shaped ``(theta_r, theta_r', theta_r'')`` at ``t`` of a reference packed at ``mp[o]`` (its
    kind at ``mp[o - 1]``): what a sampled controller samples (``hubbeam.core.sampled``)."""
    return _shaped_command(0, t, mp, o, shaper)


@borrowing_kernel
def shaped_torque(kind, t, y, v, mp, shaper, hub):
    """Torque applied to a free hub at ``t`` in the state ``(y, y')`` under the shaped command: a
    controller's law towards its shaped reference (the hub's angle at ``y[hub]``,
    :func:`hubbeam.core.maneuver.tracking_torque`), or the shaped open-loop torque ``sum_i A_i
    tau(t - t_i)`` (Eq. 44, a torque table)."""
    if tracks_reference(kind):
        return tracking_torque(kind, shaped_reference(kind, t, mp, shaper), y, v, mp, hub)
    tau = shaper[1, 0] * open_loop_torque(kind, t - shaper[0, 0], mp)
    for i in range(1, shaper.shape[1]):
        tau += shaper[1, i] * open_loop_torque(kind, t - shaper[0, i], mp)
    return tau
