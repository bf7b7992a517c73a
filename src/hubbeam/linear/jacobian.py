"""The second route to the linear models: central differences of the jitted equations of motion.

The accelerations of the general equations (``hubbeam.core.eom.mass_matrix_and_force`` with the
damping forces of ``add_damping``), ``a = M(y)^-1 F(y, y', u)`` on the free coordinates, are
differenced about the steady spin of :mod:`hubbeam.linear.statespace` (same operating point, same
states), giving ``Az = da/dz``, ``Av = da/dz'`` and ``Bu = da/du`` column by column. Nothing of the
assembled route is used but the operating point and the output rows, so the two routes check each
other.

Step and error (``docs/linear-models.md``): a central difference of step ``h`` has the truncation
error ``h^2 |f'''| / 6`` and the rounding error ``~ eps |f| / h``. The equations are at most
quadratic in the rates and linear in the input, so those columns carry rounding error only. In
a coordinate the nonlinear terms match the linear ones at an amplitude ``s``
(:func:`coordinate_scales`), and ``h = eps^(1/3) s`` balances the two errors at ``~ eps^(2/3) =
4e-11`` relative. Rates are stepped by ``h`` times the first bending frequency of the held beam
(their scale), the input by the torque or the acceleration that gives the hub that frequency
squared.
"""

from __future__ import annotations

import numpy as np

from hubbeam.core import eom
from hubbeam.linear.statespace import (
    LinearModel,
    check_matrices,
    check_request,
    check_speed,
    checked_damping,
    state_space,
)
from hubbeam.model.linearised import axial_stretch

#: relative step of the central differences, eps^(1/3)
RELATIVE_STEP = np.finfo(float).eps ** (1.0 / 3.0)


def coordinate_scales(sm) -> np.ndarray:
    """The amplitude of each coordinate at which its nonlinear terms match its linear ones.

    ``theta``: 1 rad (it only enters through its rates). ``q1`` and ``q2``: ``sqrt(Jb)`` (the
    mass matrix's ``2 V1 q1``, ``q1^T M1 q1`` against ``Jb``), and for ``q2_i`` at most
    ``sqrt(r / S_ii(L))``, where the tip's foreshortening ``q2^T S(L) q2 / 2`` reaches the
    radius of gyration ``r = sqrt(Jb / m)`` (``m`` the beam and tip mass): the higher modes, with
    their steeper slopes, foreshorten at smaller amplitudes.
    """
    n = sm.M2.shape[0]
    scale = np.sqrt(sm.Jb)
    gyration = np.sqrt(sm.Jb / np.sum(sm.w))
    q2 = np.minimum(scale, np.sqrt(gyration / np.diag(sm.SL)))
    return np.concatenate([[1.0], np.full(n, scale), q2])


def steady_state(sm, traits, speed, q1s):
    """Full-length ``(y, v)`` of the steady spin and the indices of the model's coordinates."""
    n = sm.M2.shape[0]
    y = np.zeros(1 + 2 * n)
    v = np.zeros(1 + 2 * n)
    v[0] = speed
    y[1:1 + n] = q1s
    kept = np.arange(1 + 2 * n) if traits.keeps_axial else np.r_[0, 1 + n:1 + 2 * n]
    return y, v, kept


def nonlinear_accelerations(kernel, sm, C, hub, y, v, u, kept):
    """Accelerations of the coordinates ``kept``: ``M a = F`` on the free ones, ``theta'' = u``
    where the hub is prescribed (its torque then follows from the hub row and is not needed)."""
    N = y.size
    M = np.empty((N, N))
    F = np.empty(N)
    tau = u if hub == "free" else 0.0
    eom.mass_matrix_and_force(kernel, y, v, tau, sm, M, F)
    eom.add_damping(C, v, F)
    a = np.zeros(N)
    free = kept if hub == "free" else kept[1:]
    if hub != "free":
        a[0] = u
    a[free] = np.linalg.solve(M[np.ix_(free, free)], F[free] - M[free, 0] * a[0])
    return a[kept]


def differenced_rates(sm, traits, speed, hub, damping=None):
    """``(Az, Av, Bu)`` by central differences about the steady spin, and the stretch ``q1s``."""
    n = sm.M2.shape[0]
    C = checked_damping(damping, n)
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(n)
    y0, v0, kept = steady_state(sm, traits, speed, q1s)
    kernel = traits.traits
    frequency = np.sqrt(sm.K2[0, 0] / sm.M2[0, 0])
    z_steps = RELATIVE_STEP * coordinate_scales(sm)[kept]
    v_steps = z_steps * frequency
    u_step = RELATIVE_STEP * frequency**2 * (sm.Jh + sm.Jb if hub == "free" else 1.0)

    def central(dy, dv, du, step):
        plus = nonlinear_accelerations(kernel, sm, C, hub, y0 + dy, v0 + dv, du, kept)
        minus = nonlinear_accelerations(kernel, sm, C, hub, y0 - dy, v0 - dv, -du, kept)
        return (plus - minus) / (2.0 * step)

    zero = np.zeros(y0.size)
    unit = np.eye(y0.size)[kept]
    Az = np.column_stack([central(s * e, zero, 0.0, s) for s, e in zip(z_steps, unit)])
    Av = np.column_stack([central(zero, s * e, 0.0, s) for s, e in zip(v_steps, unit)])
    Bu = central(zero, zero, u_step, u_step)[:, None]
    return (Az, Av, Bu), q1s


def jacobian_model(beam, sm, model: str, speed: float, hub: str = "free", damping=None,
                   outputs=None) -> LinearModel:
    """:func:`hubbeam.linear.statespace.linear_model` by the Jacobian route (same arguments)."""
    traits, names = check_request(model, hub, outputs)
    speed = check_speed(speed)
    check_matrices(beam, sm)
    rates, q1s = differenced_rates(sm, traits, speed, hub, damping)
    return state_space(beam, sm, traits, hub, speed, names, q1s, rates)
