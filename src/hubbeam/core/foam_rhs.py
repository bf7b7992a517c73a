"""The integrator's right-hand side of TLAM, FOAM and SFOAM with the modal mass inverted once.

In these models the elastic rows of Eq. (24) have the constant mass blocks ``M1`` and ``M2``
(Eq. 16 with the tip mass); only the hub row depends on the configuration. With ``e`` the free
elastic coordinates (``(q1, q2)``, or ``q2`` for SFOAM, Eq. 40) and ``Me = diag(M1, M2)`` on them,
the elastic rows (Eqs. 29-31, 33-34, the ``D`` terms dropped for TLAM) solved for ``e''`` are
affine in the hub rate and acceleration:

    e'' = u + theta_ddot r,
    u   = thd^2 b0 + (P0 + thd^2 P1) e + (2 thd P2 + P3) e',       r = b1 + P2 e,

    P0 = -Me^-1 diag(K1, K2),     P1 = Me^-1 diag(M1, M2 - D),   P2 = Me^-1 [[0, R], [-R^T, 0]],
    P3 = -Me^-1 diag(C1, C2),     b0 = Me^-1 (V1, 0),            b1 = Me^-1 (0, -V2t),

all restricted to the free elastic coordinates, so that an evaluation costs a few ``n x n``
products instead of assembling and factoring ``M(y)``; ``C1, C2`` are the damping matrices of
the elastic coordinates (``hubbeam.model.damping``; zero by default, when ``P3 = 0`` adds exact zeros).
A tip body's rotary inertia ``Jt`` (``docs/tip-body.md``, ``g = f2'(l)``) joins the constant mass:
``Me = diag(M1, M2 + Jt g^T g)``, ``V2t = V2 + Jt g`` and ``J0`` below; ``G`` keeps ``M2`` (the
centrifugal terms of the translating masses).
For a prescribed hub (Eq. 43, a speed table) theta_ddot is known (shaped by the command shaper,
``hubbeam.core.shaping``, as is the torque of a free hub). For a free hub (Eq. 44, a
torque table, PD, state feedback or a sampled controller's held input, through the hub's drive
if it has one, ``hubbeam.core.drive``) the hub row ``m00 theta_ddot + c . e'' = tau + Q_theta``
(Eqs. 25-27, 32) with ``c = C0 + C1 e = (-R q2, V2t + R^T q1)`` is solved by eliminating ``e''``
(a Schur complement of the constant block):

    theta_ddot = (tau + Q_theta - c . u) / (m00 + c . r),
    m00 = J0 + e^T G e + 2 g . e,     Q_theta = -2 thd (e^T G e' + g . e'),

with ``J0 = Jh + Jb + Jt``, ``G = diag(M1, M2 - D)`` and ``g = (V1, 0)`` (SFOAM: ``Q_theta`` deleted).
The same hub row gives the outputs of a state (:func:`foam_outputs`): the angular momentum
``p_theta = m00 thd + c . e'``, the kinetic energy ``(m00 thd^2 + 2 thd c . e' + e'^T Me e') / 2``
and, for a prescribed hub, the torque it requires, ``m00 theta_ddot + c . e'' - Q_theta``.
These are the equations :func:`hubbeam.core.eom.accelerations` solves with the full mass matrix;
the tests hold the two to rounding error.

With a compliant root (``hubbeam.core.root``) the matrices are the link's about its hinge, theta is
the root angle (always integrated) and the hub angle ``phi`` is appended. The hinge adds to the
elastic rows the force ``f`` and the coupling ``w`` to ``phi''`` (nothing to ``Me``), so that

    e'' = u + theta_ddot r + Me^-1 f - phi_ddot Me^-1 w,

and the root row (``m00``, ``c``, ``Q_theta`` as above, with the hinge's force and the spring) and
the hub row (``J_h + a^2 m``, the hub-root coupling ``m_rh`` and ``w``) are two equations in
``(theta_ddot, phi_ddot)``, solved by Cramer's rule (the hub's ``phi_ddot`` given when the maneuver
prescribes it): :func:`joint_rhs`. CFOAM, whose elastic mass blocks depend on ``q2``,
has its own (:mod:`hubbeam.core.cfoam_rhs`).
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.drive import free_hub_torque
from hubbeam.core.eom import cholesky_factor, cholesky_solve, free_coordinates
from hubbeam.core.jit import borrowing_kernel, inline_kernel, kernel
from hubbeam.core.maneuver import prescribed
from hubbeam.core.radau import register_rhs
from hubbeam.core.root import (
    DAMPING,
    HINGE_MASS,
    HUB_INERTIA,
    STIFFNESS,
    has_joint,
    hinge_terms,
    joint_rows,
    packed_joint,
    unpacked_joint,
)
from hubbeam.core.shaping import shaped_motion

#: TLAM, FOAM or SFOAM as a radau5 problem. ``P`` stacks ``P0, P1, P2, G, C1, P3, Me`` and ``b``
#: stacks ``b0, b1, g, C0`` (few array fields keep the reference-count work of every call small);
#: ``scalars = (J0, q_theta_factor)``; ``kind`` and ``mp`` the maneuver; ``work`` holds ``u, r``;
#: ``drive`` the hub's packed drive (``hubbeam.core.drive``; empty: the maneuver gives the torque);
#: ``shaper`` the command shaper (``hubbeam.core.shaping``); ``joint`` the compliant root packed
#: (``hubbeam.core.root.packed_joint``; empty: rigid) with the rows of :func:`joint_rhs` after it:
#: the Cholesky factor of ``Me`` on the free elastic coordinates (``ne`` rows), their indices in
#: ``(q1, q2)``, the full-length state ``(theta, q1, q2, phi)`` (positions, rates), the hinge's
#: coupling and force on ``(q1, q2)``, ``Me^-1 w`` and ``Me^-1 f``.
FoamProblem = namedtuple("FoamProblem", "kind mp P b scalars work drive shaper joint")

P0, P1, P2, G, C1, P3, ME = range(7)
B0, B1, G_VEC, C0 = range(4)


@kernel
def foam_problem(inputs):
    """The :data:`FoamProblem` of the :class:`~hubbeam.core.inputs.SimulationInputs` ``inputs``
    of TLAM, FOAM or SFOAM (its traits: ``softening_terms`` keeps ``D``, ``keeps_axial`` keeps
    ``q1``, ``hub_velocity_force`` keeps ``Q_theta``) under its maneuver with the damping
    matrices ``C = [C1, C2]``.

    Assembled with plain loops and the Cholesky factor of ``Me`` (numpy's stacking and inverse
    would cost seconds of compilation in every process that builds the kernel)."""
    traits, kind, mp, C, sm = inputs.traits, inputs.kind, inputs.mp, inputs.C, inputs.sm
    n = sm.M1.shape[0]
    m = 2 * n
    cD = 1.0 if traits.softening_terms else 0.0
    # on (q1, q2): diag(K1, K2), G = diag(M1, M2 - D), [[0, R], [-R^T, 0]], diag(C1, C2),
    # Me = diag(M1, M2 + Jt g^T g), and the vectors (V1, 0), (0, -V2t), V2t = V2 + Jt g
    A = np.zeros((5, m, m))
    f = np.zeros((2, m))
    for i in range(n):
        f[0, i] = sm.V1[i]
        f[1, n + i] = -sm.V2[i]
        for j in range(n):
            A[0, i, j] = sm.K1[i, j]
            A[0, n + i, n + j] = sm.K2[i, j]
            A[1, i, j] = sm.M1[i, j]
            A[1, n + i, n + j] = sm.M2[i, j] - cD * sm.D[i, j]
            A[2, i, n + j] = sm.R[i, j]
            A[2, n + i, j] = -sm.R[j, i]
            A[3, i, j] = C[0, i, j]
            A[3, n + i, n + j] = C[1, i, j]
            A[4, i, j] = sm.M1[i, j]
            A[4, n + i, n + j] = sm.M2[i, j]
    if sm.Jt != 0.0:  # the tip body's rotary inertia, g = f2'(l)
        for i in range(n):
            f[1, n + i] -= sm.Jt * sm.dF2t[i]
            for j in range(n):
                A[4, n + i, n + j] += sm.Jt * sm.dF2t[i] * sm.dF2t[j]
    # Me^-1 times the first four matrices (column by column) and the two vectors
    factor = A[4].copy()
    cholesky_factor(factor)
    X = np.empty((4, m, m))
    x = np.empty(m)
    for k in range(4):
        for j in range(m):
            for i in range(m):
                x[i] = A[k, i, j]
            cholesky_solve(factor, x)
            for i in range(m):
                X[k, i, j] = x[i]
    fx = f.copy()
    cholesky_solve(factor, fx[0])
    cholesky_solve(factor, fx[1])
    # free elastic coordinates as indices into (q1, q2)
    free = free_coordinates(inputs)
    elastic = free[(free > 0) & (free <= m)] - 1
    ne = elastic.shape[0]
    P = np.empty((7, ne, ne))
    b = np.empty((4, ne))
    for i in range(ne):
        r = elastic[i]
        b[B0, i] = fx[0, r]
        b[B1, i] = fx[1, r]
        b[G_VEC, i] = f[0, r]
        b[C0, i] = -f[1, r] if r >= n else 0.0  # V2t on q2
        for j in range(ne):
            c = elastic[j]
            P[P0, i, j] = -X[0, r, c]
            P[P1, i, j] = X[1, r, c]
            P[P2, i, j] = X[2, r, c]
            P[G, i, j] = A[1, r, c]
            P[C1, i, j] = -A[2, r, c]
            P[P3, i, j] = -X[3, r, c]
            P[ME, i, j] = A[4, r, c]
    q_theta_factor = 1.0 if traits.hub_velocity_force else 0.0
    scalars = np.array([sm.Jh + sm.Jb + sm.Jt, q_theta_factor])
    joint = np.zeros((0, 0))
    if has_joint(inputs.root):
        joint = packed_joint(traits, inputs.root, ne + 7)
        first = joint_rows(joint)
        factor = joint[first:first + ne, :ne]
        factor[:, :] = P[ME]
        cholesky_factor(factor)
        for i in range(ne):
            joint[first + ne, i] = elastic[i]
    return FoamProblem(kind, mp, P, b, scalars, np.empty((2, ne)), inputs.drive, inputs.shaper, joint)


@borrowing_kernel
def _hub_row(y, v, o, thd, x1, x2, ox, problem):
    """The hub row of Eq. (24) at the free elastic coordinates ``e = y[o:]``, ``e' = v[o:]``:
    ``(m00, Q_theta, c . x1[ox:], c . x2[ox:])`` with ``m00`` (Eq. 25), ``c = C0 + C1 e``
    (Eqs. 26-27) and ``Q_theta`` (Eq. 32; zero for SFOAM) as in the module docstring."""
    P = problem.P
    b = problem.b
    ne = problem.work.shape[1]
    m00 = problem.scalars[0]
    gee = 0.0  # e^T G e' + g . e'
    c_1 = 0.0
    c_2 = 0.0
    for i in range(ne):
        ge = b[G_VEC, i]
        ci = b[C0, i]
        for j in range(ne):
            ge += P[G, i, j] * y[o + j]
            ci += P[C1, i, j] * y[o + j]
        m00 += (ge + b[G_VEC, i]) * y[o + i]
        gee += ge * v[o + i]
        c_1 += ci * x1[ox + i]
        c_2 += ci * x2[ox + i]
    return m00, -2.0 * thd * gee * problem.scalars[1], c_1, c_2


@inline_kernel
def _elastic_rates(y, v, o, thd, problem):
    """``u`` and ``r`` of ``e'' = u + theta_ddot r`` (module docstring) into ``problem.work`` at the
    free elastic coordinates ``e = y[o:o + ne]``."""
    P = problem.P
    b = problem.b
    u = problem.work[0]
    r = problem.work[1]
    thd2 = thd * thd
    for i in range(u.shape[0]):
        ui = thd2 * b[B0, i]
        ri = b[B1, i]
        for j in range(u.shape[0]):
            ej = y[o + j]
            ui += ((P[P0, i, j] + thd2 * P[P1, i, j]) * ej
                   + (2.0 * thd * P[P2, i, j] + P[P3, i, j]) * v[o + j])
            ri += P[P2, i, j] * ej
        u[i] = ui
        r[i] = ri


@borrowing_kernel
def joint_rhs(t, y, v, a, problem):
    """:func:`foam_rhs` with a compliant root: accelerations of theta, ``e`` and, unless
    prescribed, the hub angle phi (the last free coordinate), from the two hub rows (module
    docstring)."""
    joint = problem.joint
    u = problem.work[0]
    r = problem.work[1]
    nf = y.shape[0]
    ne = u.shape[0]
    traits, root = unpacked_joint(joint)
    m = 2 * root.p1.shape[0]
    first = joint_rows(joint)
    factor = joint[first:first + ne, :ne]
    elastic = joint[first + ne]
    yf = joint[first + ne + 1]
    vf = joint[first + ne + 2]
    coupling = joint[first + ne + 3]
    force = joint[first + ne + 4]
    w_hat = joint[first + ne + 5]
    f_hat = joint[first + ne + 6]
    free_hub = nf == ne + 2
    thd = v[0]
    if free_hub:
        phi = y[nf - 1]
        phd = v[nf - 1]
        phdd = 0.0
    else:
        phi, phd, phdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)
    _elastic_rates(y, v, 1, thd, problem)
    # the full-length state (theta, q1, q2, phi); q1 held at zero where not integrated
    for i in range(m):
        yf[1 + i] = 0.0
        vf[1 + i] = 0.0
    for i in range(ne):
        yf[1 + int(elastic[i])] = y[1 + i]
        vf[1 + int(elastic[i])] = v[1 + i]
    yf[0] = y[0]
    vf[0] = thd
    yf[m + 1] = phi
    vf[m + 1] = phd
    root_hub, root_force, hub_force = hinge_terms(traits, root, yf[:m + 2], vf[:m + 2], coupling, force)
    for i in range(ne):
        w_hat[i] = coupling[int(elastic[i])]
        f_hat[i] = force[int(elastic[i])]
    cholesky_solve(factor, w_hat[:ne])
    cholesky_solve(factor, f_hat[:ne])
    m00, q_theta, c_u, c_r = _hub_row(y, v, 1, thd, u, r, 0, problem)
    _, _, c_w, c_f = _hub_row(y, v, 1, thd, w_hat, f_hat, 0, problem)
    w_u = w_r = w_w = w_f = 0.0  # w . u, w . r, w . Me^-1 w, w . Me^-1 f
    for i in range(ne):
        wi = coupling[int(elastic[i])]
        w_u += wi * u[i]
        w_r += wi * r[i]
        w_w += wi * w_hat[i]
        w_f += wi * f_hat[i]
    twist = root.scalars[STIFFNESS] * (phi - y[0]) + root.scalars[DAMPING] * (phd - thd)
    a11 = m00 + c_r
    a12 = root_hub - c_w
    b1 = q_theta + root_force + twist - c_u - c_f
    if free_hub:
        tau = free_hub_torque(problem.drive, problem.kind, t, y, v, problem.mp, problem.shaper, nf - 1)
        a21 = root_hub + w_r
        a22 = root.scalars[HUB_INERTIA] + root.scalars[HINGE_MASS] - w_w
        b2 = tau + hub_force - twist - w_u - w_f
        det = a11 * a22 - a12 * a21
        thdd = (b1 * a22 - a12 * b2) / det
        phdd = (a11 * b2 - a21 * b1) / det
        a[nf - 1] = phdd
    else:
        thdd = (b1 - a12 * phdd) / a11
    a[0] = thdd
    for i in range(ne):
        a[1 + i] = u[i] + thdd * r[i] + f_hat[i] - phdd * w_hat[i]


@borrowing_kernel
def _clamped_rhs(t, y, v, a, problem):
    """:func:`foam_rhs` on the rigid root: ``e'' = u + theta_ddot r`` with theta_ddot prescribed or,
    for a free hub, from the hub row with ``e''`` eliminated (module docstring). Returns the hub's
    rate and acceleration and the applied torque (0 for a prescribed hub)."""
    u = problem.work[0]
    r = problem.work[1]
    o = 0 if prescribed(problem.kind) else 1
    ne = y.shape[0] - o
    tau = 0.0
    if o == 0:
        thd, thdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)[1:]
    else:
        thd = v[0]
        thdd = 0.0
    _elastic_rates(y, v, o, thd, problem)
    if o == 1:
        # hub row (Eqs. 25-27, 32) with e'' eliminated
        m00, q_theta, c_u, c_r = _hub_row(y, v, 1, thd, u, r, 0, problem)
        tau = free_hub_torque(problem.drive, problem.kind, t, y, v, problem.mp, problem.shaper, 0)
        thdd = (tau + q_theta - c_u) / (m00 + c_r)
        a[0] = thdd
    for i in range(ne):
        a[o + i] = u[i] + thdd * r[i]
    return thd, thdd, tau


@borrowing_kernel
def foam_rhs(t, y, v, a, problem):
    """Accelerations ``a`` of the free coordinates (theta first unless prescribed, then ``e``):
    :func:`_clamped_rhs`, or with a compliant root :func:`joint_rhs`."""
    if problem.joint.shape[0] > 0:
        joint_rhs(t, y, v, a, problem)
    else:
        _clamped_rhs(t, y, v, a, problem)


@borrowing_kernel
def foam_outputs(t, y, v, a, problem):
    """Accelerations ``a`` of the free coordinates (:func:`foam_rhs` on the rigid root) and
    ``(torque, Q_theta, kinetic energy, angular momentum)`` of the state ``(y, v)`` (free
    coordinates, as in :func:`foam_rhs`), from the hub row of Eq. (24) (Eqs. 25-27, 32; see the
    module docstring). ``torque`` is the applied torque of a free hub, or the one a prescribed
    hub requires."""
    thd, thdd, tau = _clamped_rhs(t, y, v, a, problem)
    P = problem.P
    o = 0 if prescribed(problem.kind) else 1
    ne = y.shape[0] - o
    m00, q_theta, c_v, c_a = _hub_row(y, v, o, thd, v, a, o, problem)
    eMe = 0.0  # e'^T Me e'
    for i in range(ne):
        mv = 0.0
        for j in range(ne):
            mv += P[ME, i, j] * v[o + j]
        eMe += v[o + i] * mv
    if o == 0:
        tau = m00 * thdd + c_a - q_theta
    kinetic = 0.5 * (m00 * thd * thd + 2.0 * thd * c_v + eMe)
    return tau, q_theta, kinetic, m00 * thd + c_v


register_rhs(FoamProblem, foam_rhs)
