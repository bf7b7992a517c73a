"""Jitted hub maneuvers of Section 4.

``PRESCRIBED``: the spin-up of Eq. (43) with the factor ``t`` the transcription lost (reproduction
note 1); ``mp = [wf, tf]``. The hub angle, rate and acceleration are

    theta_dot  = wf/tf * t - wf/(2 pi) * sin(2 pi t / tf)             (0 <= t <= tf)
    theta      = wf/(2 tf) * t^2 + wf tf/(4 pi^2) * (cos(2 pi t / tf) - 1)
    theta_ddot = wf/tf * (1 - cos(2 pi t / tf))

and theta_dot = wf, theta_ddot = 0 afterwards.

``TORQUE``: the rest-to-rest torque pulse of Eq. (44) with ``T = tf`` (note 8); ``mp = [tau_max, tf]``:
tau = tau_max sin(2 pi t / tf) for 0 <= t <= tf and zero afterwards; the hub is free.
"""

import math

from hubbeam.core.jit import borrowing_kernel

PRESCRIBED = 0
TORQUE = 1


@borrowing_kernel
def hub_motion(t, mp):
    """Prescribed hub angle, rate and acceleration of Eq. (43) at time ``t``."""
    wf = mp[0]
    tf = mp[1]
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
def applied_torque(t, mp):
    """Hub torque of Eq. (44) at time ``t`` (zero outside the pulse)."""
    tau_max = mp[0]
    tf = mp[1]
    if t <= 0.0 or t >= tf:
        return 0.0
    return tau_max * math.sin(2.0 * math.pi * t / tf)
