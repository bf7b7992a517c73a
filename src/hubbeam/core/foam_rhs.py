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
the tests hold the two to rounding error. CFOAM, whose elastic mass blocks depend on ``q2``,
has its own (:mod:`hubbeam.core.cfoam_rhs`).
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.drive import drive_torque
from hubbeam.core.eom import cholesky_factor, cholesky_solve, free_dofs
from hubbeam.core.jit import borrowing_kernel, kernel
from hubbeam.core.maneuver import prescribed
from hubbeam.core.radau import register_rhs
from hubbeam.core.shaping import shaped_motion, shaped_torque

#: TLAM, FOAM or SFOAM as a radau5 problem. ``P`` stacks ``P0, P1, P2, G, C1, P3, Me`` and ``b``
#: stacks ``b0, b1, g, C0`` (few array fields keep the reference-count work of every call small);
#: ``scalars = (J0, q_theta_factor)``; ``kind`` and ``mp`` the maneuver; ``work`` holds ``u, r``;
#: ``drive`` the hub's packed drive (``hubbeam.core.drive``; empty: the maneuver gives the torque);
#: ``shaper`` the command shaper (``hubbeam.core.shaping``).
FoamProblem = namedtuple("FoamProblem", "kind mp P b scalars work drive shaper")

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
    free = free_dofs(traits, kind, n)
    elastic = free[free > 0] - 1
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
    return FoamProblem(kind, mp, P, b, scalars, np.empty((2, ne)), inputs.drive, inputs.shaper)


@borrowing_kernel
def _hub_row(y, v, o, thd, x1, x2, ox, problem):
    """The hub row of Eq. (24) at the free elastic coordinates ``e = y[o:]``, ``e' = v[o:]``:
    ``(m00, Q_theta, c . x1[ox:], c . x2[ox:])`` with ``m00`` (Eq. 25), ``c = C0 + C1 e``
    (Eqs. 26-27) and ``Q_theta`` (Eq. 32; zero for SFOAM) as in the module docstring."""
    P = problem.P
    b = problem.b
    ne = y.shape[0] - o
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


@borrowing_kernel
def foam_rhs(t, y, v, a, problem):
    """Accelerations ``a`` of the free coordinates (theta first unless prescribed, then ``e``)."""
    P = problem.P
    b = problem.b
    u = problem.work[0]
    r = problem.work[1]
    o = 0 if prescribed(problem.kind) else 1
    ne = y.shape[0] - o
    if o == 0:
        thd, thdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)[1:]
    else:
        thd = v[0]
        thdd = 0.0
    thd2 = thd * thd
    for i in range(ne):
        ui = thd2 * b[B0, i]
        ri = b[B1, i]
        for j in range(ne):
            ej = y[o + j]
            ui += ((P[P0, i, j] + thd2 * P[P1, i, j]) * ej
                   + (2.0 * thd * P[P2, i, j] + P[P3, i, j]) * v[o + j])
            ri += P[P2, i, j] * ej
        u[i] = ui
        r[i] = ri
    if o == 1:
        # hub row (Eqs. 25-27, 32) with e'' eliminated
        m00, q_theta, c_u, c_r = _hub_row(y, v, 1, thd, u, r, 0, problem)
        tau = drive_torque(problem.drive, shaped_torque(problem.kind, t, y, v, problem.mp, problem.shaper), thd)
        thdd = (tau + q_theta - c_u) / (m00 + c_r)
        a[0] = thdd
    for i in range(ne):
        a[o + i] = u[i] + thdd * r[i]


@borrowing_kernel
def foam_outputs(t, y, v, a, problem):
    """Accelerations ``a`` of the free coordinates (:func:`foam_rhs`) and
    ``(torque, Q_theta, kinetic energy, angular momentum)`` of the state ``(y, v)`` (free
    coordinates, as in :func:`foam_rhs`), from the hub row of Eq. (24) (Eqs. 25-27, 32; see the
    module docstring). ``torque`` is the applied torque of a free hub, or the one a prescribed
    hub requires."""
    foam_rhs(t, y, v, a, problem)
    P = problem.P
    o = 0 if prescribed(problem.kind) else 1
    ne = y.shape[0] - o
    if o == 0:
        thd, thdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)[1:]
        tau = 0.0
    else:
        thd = v[0]
        thdd = a[0]
        tau = drive_torque(problem.drive, shaped_torque(problem.kind, t, y, v, problem.mp, problem.shaper), thd)
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
