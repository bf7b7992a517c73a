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

With a compliant root (``root_spring``) the equations are the link's about its hinge with the
joint's terms (``hubbeam.core.root.add_joint``), the hub angle ``phi`` appended (differenced as
``theta``) and the input on it: the same kernels the simulations integrate.
"""

from __future__ import annotations

import numpy as np

from hubbeam.core import eom
from hubbeam.core.inputs import NO_ROOT
from hubbeam.core.root import add_joint, has_joint
from hubbeam.linear.statespace import (
    LinearModel,
    check_matrices,
    check_request,
    check_speed,
    checked_damping,
    state_space,
)
from hubbeam.model.linearised import axial_stretch
from hubbeam.model.root import RootSpring, checked_spring, joint_inputs

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


def steady_state(sm, traits, speed, q1s, joint: bool = False):
    """Full-length ``(y, v)`` of the steady spin and the indices of the model's coordinates (with a
    compliant root, ``joint``, the hub angle appended, turning with the root)."""
    n = sm.M2.shape[0]
    N = 2 + 2 * n if joint else 1 + 2 * n
    y = np.zeros(N)
    v = np.zeros(N)
    v[0] = speed
    if joint:
        v[-1] = speed
    y[1:1 + n] = q1s
    kept = np.arange(N) if traits.keeps_axial else np.r_[0, 1 + n:N]
    return y, v, kept


def nonlinear_accelerations(kernel, sm, C, hub, y, v, u, kept, root=NO_ROOT):
    """Accelerations of the coordinates ``kept``: ``M a = F`` on the free ones, the hub angle's
    ``= u`` where the hub is prescribed (its torque then follows from the hub row and is not
    needed); with a compliant root ``root`` (``sm`` the link's matrices) the joint's equations and
    the hub angle last."""
    N = y.size
    M = np.empty((N, N))
    F = np.empty(N)
    tau = u if hub == "free" else 0.0
    if has_joint(root):
        eom.mass_matrix_and_force(kernel, y, v, 0.0, sm, M, F)
        add_joint(kernel, root, y, v, tau, M, F, np.empty((2, N - 2)))
    else:
        eom.mass_matrix_and_force(kernel, y, v, tau, sm, M, F)
    eom.add_damping(C, v, F)
    a = np.zeros(N)
    index = N - 1 if has_joint(root) else 0
    free = kept if hub == "free" else kept[kept != index]
    if hub != "free":
        a[index] = u
    a[free] = np.linalg.solve(M[np.ix_(free, free)], F[free] - M[free, index] * a[index])
    return a[kept]


def differenced_rates(sm, traits, speed, hub, damping=None, root_spring: RootSpring | None = None):
    """``(Az, Av, Bu)`` by central differences about the steady spin, and the stretch ``q1s``
    (with a compliant root ``root_spring``, of ``(theta, [q1], q2, phi)``)."""
    n = sm.M2.shape[0]
    C = checked_damping(damping, n)
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(n)
    joint = root_spring is not None
    y0, v0, kept = steady_state(sm, traits, speed, q1s, joint)
    link, root = joint_inputs(sm, root_spring)
    kernel = traits.traits
    frequency = np.sqrt(sm.K2[0, 0] / sm.M2[0, 0])
    scales = coordinate_scales(sm)
    z_steps = RELATIVE_STEP * (np.append(scales, 1.0) if joint else scales)[kept]
    v_steps = z_steps * frequency
    u_step = RELATIVE_STEP * frequency**2 * (sm.Jh + sm.Jb if hub == "free" else 1.0)

    def central(dy, dv, du, step):
        plus = nonlinear_accelerations(kernel, link, C, hub, y0 + dy, v0 + dv, du, kept, root)
        minus = nonlinear_accelerations(kernel, link, C, hub, y0 - dy, v0 - dv, -du, kept, root)
        return (plus - minus) / (2.0 * step)

    zero = np.zeros(y0.size)
    unit = np.eye(y0.size)[kept]
    Az = np.column_stack([central(s * e, zero, 0.0, s) for s, e in zip(z_steps, unit)])
    Av = np.column_stack([central(zero, s * e, 0.0, s) for s, e in zip(v_steps, unit)])
    Bu = central(zero, zero, u_step, u_step)[:, None]
    return (Az, Av, Bu), q1s


def jacobian_model(beam, sm, model: str, speed: float, hub: str = "free", damping=None,
                   outputs=None, root_spring: RootSpring | None = None) -> LinearModel:
    """:func:`hubbeam.linear.statespace.linear_model` by the Jacobian route (same arguments)."""
    root_spring = checked_spring(root_spring)
    traits, names = check_request(model, hub, outputs, root_spring is not None)
    speed = check_speed(speed)
    check_matrices(beam, sm)
    rates, q1s = differenced_rates(sm, traits, speed, hub, damping, root_spring)
    return state_space(beam, sm, traits, hub, speed, names, q1s, rates, root_spring)
