"""Jitted equations of motion of TLAM, FOAM, SFOAM and CFOAM (Section 3).

Every model is written in the generalised coordinates ``y = (theta, q1, q2)`` (size ``1 + 2n``) as

    M(y) y'' = F(t, y, y'),        F_theta = tau + Q_theta,

the form of Eq. (24) with the gyroscopic, stiffness and velocity terms moved to the right-hand side.
``sm`` is the :class:`hubbeam.model.matrices.SystemMatrices` namedtuple (tip-mass terms included).

* FOAM, Eqs. (25)-(34) without the Delta terms, with M_thq1 = -q2^T R^T and
  M_thq2 = V2 + q1^T R (reproduction note 2).
* TLAM: FOAM without the underlined ``D`` terms of Eqs. (25), (31), (32).
* SFOAM, Eq. (40): q1 held at zero and Q_theta deleted.
* CFOAM: Lagrange's equations of the exact kinetic energy (Eqs. 8-9) of the deformation field
  u = w1 + wc, v = w2 (Eq. 2-3), derived in ``docs/cfoam.md``. With the rotating-frame position
  ``(X, Y) = (rA + x + f1 q1 - q2^T S q2 / 2, f2 q2)`` of every mass point, its Jacobian
  ``J = dr/dy`` (rotating components) and the velocity-only part ``b`` of its acceleration,

      M = Jh e e^T + sum_k w_k J_k^T J_k,   F = tau e - K y - sum_k w_k J_k^T b_k,

  summed over the point cloud (Gauss nodes of the beam and the tip body's centre).

A tip body's rotary inertia ``Jt`` (``SystemMatrices.Jt``, ``docs/tip-body.md``) adds
``Jt (theta' + f2'(l) q2')^2 / 2`` to the kinetic energy of every model: constant entries of the
mass matrix (:func:`add_rotary_inertia`) and no force.

A compliant root (``hubbeam.core.root``: a torsional spring and damper between the hub and the
beam's root, the hub angle ``phi`` appended to ``y``) adds its hinge's terms, the spring and the
damper to the link's equations about its hinge (:func:`equations`); the hub torque then acts on
``phi``.

A model enters as its :class:`~hubbeam.core.inputs.ModelTraits` (``traits``), built from the one
table of models (``hubbeam.model.models``): the kernels branch on what a model keeps, never on its name.

The kernels only use loops over small arrays: for the 5 to 20 modes of this study explicit loops
beat BLAS calls. These are the general equations (dataset outputs, the tests' reference); the
integrator's right-hand sides, which allocate nothing per call, are ``foam_rhs`` and ``cfoam_rhs``.
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.drive import free_hub_torque
from hubbeam.core.jit import borrowing_kernel, kernel
from hubbeam.core.maneuver import prescribed
from hubbeam.core.root import add_joint, damper_power, has_joint, hub_index, spring_energy, spring_torque
from hubbeam.core.shaping import shaped_motion


@kernel
def free_indices(traits, n, theta, phi):
    """Indices of the integrated entries of ``y``: theta (0) if ``theta``, q1 if the model keeps it,
    q2, and the hub angle of a compliant root (``1 + 2 n``) if ``phi``."""
    count = n * (2 if traits.keeps_axial else 1) + int(theta) + int(phi)
    free = np.empty(count, dtype=np.int64)
    k = 0
    if theta:
        free[k] = 0
        k += 1
    if traits.keeps_axial:
        for i in range(n):
            free[k] = 1 + i
            k += 1
    for i in range(n):
        free[k] = 1 + n + i
        k += 1
    if phi:
        free[k] = 1 + 2 * n
    return free


@kernel
def free_dofs(traits, kind, n):
    """Indices of ``y`` that are integrated: theta unless prescribed, q1 if the model keeps it."""
    return free_indices(traits, n, not prescribed(kind), False)


@kernel
def free_coordinates(inputs):
    """Indices of the integrated coordinates of the :class:`~hubbeam.core.inputs.SimulationInputs`
    ``inputs``: :func:`free_dofs`, and with a compliant root (``y = (theta, q1, q2, phi)``) theta
    always (the link turns on the spring), q1 if the model keeps it, q2, and the hub angle phi
    unless the maneuver prescribes it."""
    n = inputs.sm.M1.shape[0]
    if not has_joint(inputs.root):
        return free_dofs(inputs.traits, inputs.kind, n)
    return free_indices(inputs.traits, n, True, not prescribed(inputs.kind))


@kernel
def coordinate_count(inputs):
    """The length of ``y``: ``1 + 2 n``, one more with a compliant root (the hub angle)."""
    N = 1 + 2 * inputs.sm.M1.shape[0]
    if has_joint(inputs.root):
        return N + 1
    return N


@borrowing_kernel
def _quad(A, a, b, n, off_a, off_b):
    """a[off_a:off_a+n]^T A b[off_b:off_b+n]."""
    s = 0.0
    for i in range(n):
        ai = a[off_a + i]
        if ai != 0.0:
            row = 0.0
            for j in range(n):
                row += A[i, j] * b[off_b + j]
            s += ai * row
    return s


@borrowing_kernel
def add_damping(C, v, F):
    """Subtract the damping forces ``C1 q1'`` and ``C2 q2'`` (``C = [C1, C2]``, shape
    ``(2, n, n)``, from ``hubbeam.model.damping``) from the q1 and q2 rows of ``F``."""
    n = C.shape[1]
    for b in range(2):
        o = 1 + b * n
        for i in range(n):
            s = 0.0
            for j in range(n):
                s += C[b, i, j] * v[o + j]
            F[o + i] -= s


@borrowing_kernel
def dissipation_rate(C, v):
    """Power dissipated by the damping forces, ``q1'^T C1 q1' + q2'^T C2 q2'``."""
    n = C.shape[1]
    return _quad(C[0], v, v, n, 1, 1) + _quad(C[1], v, v, n, 1 + n, 1 + n)


@borrowing_kernel
def add_rotary_inertia(sm, M):
    """Add the tip body's rotary inertia to the mass matrix ``M`` of ``y = (theta, q1, q2)``: the
    rates' Hessian of ``Jt (theta' + g q2')^2 / 2``, ``g = f2'(l)`` (``sm.dF2t``): ``Jt`` on the
    hub, ``Jt g`` between the hub and ``q2``, ``Jt g^T g`` on ``q2``."""
    n = sm.M1.shape[0]
    o2 = 1 + n
    Jt = sm.Jt
    M[0, 0] += Jt
    for i in range(n):
        c = Jt * sm.dF2t[i]
        M[0, o2 + i] += c
        M[o2 + i, 0] += c
        for j in range(n):
            M[o2 + i, o2 + j] += c * sm.dF2t[j]


@borrowing_kernel
def _elastic_forces(cD, y, v, sm, out):
    """The q1 and q2 rows of FOAM's right-hand side (``cD = 0``: TLAM) into ``out[1:]``:
    ``Q_q1 - K_q1q1 q1 - 2 thd G_q1q2 q2'`` and ``-K_q2q2 q2 - 2 thd G_q2q1 q1'`` (Eqs. 29-31,
    33-34)."""
    n = sm.M1.shape[0]
    o1 = 1
    o2 = 1 + n
    thd = v[0]
    thd2 = thd * thd
    for i in range(n):
        f1 = thd2 * sm.V1[i]
        f2 = 0.0
        for j in range(n):
            f1 += (-(sm.K1[i, j] - thd2 * sm.M1[i, j]) * y[o1 + j]
                   + 2.0 * thd * sm.R[i, j] * v[o2 + j])
            f2 += (-(sm.K2[i, j] - thd2 * sm.M2[i, j] + cD * thd2 * sm.D[i, j]) * y[o2 + j]
                   - 2.0 * thd * sm.R[j, i] * v[o1 + j])
        out[o1 + i] = f1
        out[o2 + i] = f2


@borrowing_kernel
def foam_system(traits, y, v, tau, sm, M, F):
    """Mass matrix and force of the first-order equations of a model with ``traits``: FOAM
    (Eqs. 24-34), TLAM (no ``softening_terms``: no D terms) or SFOAM (Eq. 40: no
    ``keeps_axial``, no ``hub_velocity_force``); for CFOAM's traits, FOAM's."""
    n = sm.M1.shape[0]
    o1 = 1
    o2 = 1 + n
    cD = 1.0 if traits.softening_terms else 0.0
    thd = v[0]

    # M_thth, Eq. (25)
    m00 = sm.Jh + sm.Jb + _quad(sm.M1, y, y, n, o1, o1) + _quad(sm.M2, y, y, n, o2, o2)
    for i in range(n):
        m00 += 2.0 * sm.V1[i] * y[o1 + i]
    m00 -= cD * _quad(sm.D, y, y, n, o2, o2)
    M[0, 0] = m00

    for i in range(n):
        # M_thq1 = -(R q2)^T (note 2), M_thq2 = V2 + q1^T R (Eq. 27)
        rq2 = 0.0
        q1r = 0.0
        for j in range(n):
            rq2 += sm.R[i, j] * y[o2 + j]
            q1r += y[o1 + j] * sm.R[j, i]
        M[0, o1 + i] = -rq2
        M[o1 + i, 0] = -rq2
        M[0, o2 + i] = sm.V2[i] + q1r
        M[o2 + i, 0] = sm.V2[i] + q1r
        for j in range(n):
            M[o1 + i, o1 + j] = sm.M1[i, j]
            M[o2 + i, o2 + j] = sm.M2[i, j]
            M[o1 + i, o2 + j] = 0.0
            M[o2 + i, o1 + j] = 0.0

    # Q_theta, Eq. (32)
    q_theta = _quad(sm.M1, y, v, n, o1, o1) + _quad(sm.M2, y, v, n, o2, o2)
    for i in range(n):
        q_theta += sm.V1[i] * v[o1 + i]
    q_theta -= cD * _quad(sm.D, y, v, n, o2, o2)
    q_theta *= -2.0 * thd
    F[0] = tau + q_theta

    _elastic_forces(cD, y, v, sm, F)
    if sm.Jt != 0.0:
        add_rotary_inertia(sm, M)

    if not traits.keeps_axial:
        # Eq. (40): q1 rows decoupled (held at zero by the caller)
        for i in range(n):
            M[0, o1 + i] = 0.0
            M[o1 + i, 0] = 0.0
            F[o1 + i] = 0.0
    if not traits.hub_velocity_force:
        F[0] = tau  # Eq. (40): Q_theta deleted


@kernel
def _cfoam_system(y, v, tau, sm, M, F):
    """Mass matrix and force of CFOAM from the exact kinetic energy (see module docstring).

    Evaluated block by block: with ``J = [[-Y, f1, -(S q2)^T], [X, 0, f2]]`` the q1-q1 block of
    ``sum w J^T J`` is the constant ``M1`` and the q2-q2 block is ``M2 + sum w (S q2)(S q2)^T``,
    so only the configuration-dependent parts are summed over the point cloud.
    """
    n = sm.M1.shape[0]
    N = 1 + 2 * n
    o1 = 1
    o2 = 1 + n
    thd = v[0]
    thd2 = thd * thd
    for i in range(N):
        F[i] = 0.0
        for j in range(N):
            M[i, j] = 0.0
    for i in range(n):
        for j in range(n):
            M[o1 + i, o1 + j] = sm.M1[i, j]
            M[o2 + i, o2 + j] = sm.M2[i, j]
    m00 = sm.Jh
    Sq2 = np.empty(n)
    for k in range(sm.x.shape[0]):
        wk = sm.w[k]
        if wk == 0.0:
            continue
        X = sm.rA + sm.x[k]
        Y = 0.0
        Xd = 0.0
        Yd = 0.0
        q2dSq2d = 0.0
        half_q2Sq2 = 0.0
        for i in range(n):
            s = 0.0
            sd = 0.0
            for j in range(n):
                s += sm.S[k, i, j] * y[o2 + j]
                sd += sm.S[k, i, j] * v[o2 + j]
            Sq2[i] = s
            half_q2Sq2 += 0.5 * y[o2 + i] * s
            q2dSq2d += v[o2 + i] * sd
            X += sm.F1[k, i] * y[o1 + i]
            Y += sm.F2[k, i] * y[o2 + i]
            Xd += sm.F1[k, i] * v[o1 + i] - s * v[o2 + i]
            Yd += sm.F2[k, i] * v[o2 + i]
        X -= half_q2Sq2
        # velocity-only part (bx, by) of the rotating-frame acceleration of the point
        bx = -q2dSq2d - 2.0 * thd * Yd - thd2 * X
        by = 2.0 * thd * Xd - thd2 * Y
        m00 += wk * (X * X + Y * Y)
        F[0] -= wk * (X * by - Y * bx)
        for i in range(n):
            f1 = sm.F1[k, i]
            f2 = sm.F2[k, i]
            s = Sq2[i]
            M[0, o1 + i] -= wk * Y * f1
            M[0, o2 + i] += wk * (Y * s + X * f2)
            F[o1 + i] -= wk * f1 * bx
            F[o2 + i] -= wk * (f2 * by - s * bx)
            ws = wk * s
            for j in range(n):
                M[o1 + i, o2 + j] -= wk * f1 * Sq2[j]
            for j in range(i, n):
                M[o2 + i, o2 + j] += ws * Sq2[j]
    M[0, 0] = m00
    for i in range(n):
        M[o1 + i, 0] = M[0, o1 + i]
        M[o2 + i, 0] = M[0, o2 + i]
        for j in range(n):
            M[o2 + j, o1 + i] = M[o1 + i, o2 + j]
        for j in range(i + 1, n):
            M[o2 + j, o2 + i] = M[o2 + i, o2 + j]
    for i in range(n):
        for j in range(n):
            F[o1 + i] -= sm.K1[i, j] * y[o1 + j]
            F[o2 + i] -= sm.K2[i, j] * y[o2 + j]
    F[0] += tau
    if sm.Jt != 0.0:
        add_rotary_inertia(sm, M)


@kernel
def mass_matrix_and_force(traits, y, v, tau, sm, M, F):
    """Fill the full ``M(y)`` and ``F(y, y')`` of the model with ``traits``
    (``F_theta = tau + Q_theta``), without damping (:func:`add_damping`)."""
    if traits.exact_kinetic_energy:
        _cfoam_system(y, v, tau, sm, M, F)
    else:
        foam_system(traits, y, v, tau, sm, M, F)


@borrowing_kernel
def impose_constraints(inputs, t, y, v, a):
    """Overwrite the constrained entries of y, y', y'' and return the applied torque.

    A prescribed maneuver (Eq. 43, a speed table) sets theta and its rates and applies no torque
    of its own (the torque it needs is an output); a free hub gets the torque of its maneuver
    (Eq. 44, a torque table, PD feedback on theta and theta', state feedback on the whole
    state, evaluated after a model that does not keep q1 (SFOAM) has it held at zero, a held
    input), through the hub's drive when it has one (``inputs.drive``, ``hubbeam.core.drive``). Both
    follow the command shaped by ``inputs.shaper`` (``hubbeam.core.shaping``). With a compliant
    root the hub is the hub angle ``phi``, the last coordinate (``hubbeam.core.root``).
    ``inputs``: :class:`~hubbeam.core.inputs.SimulationInputs`.
    """
    n = (y.shape[0] - 1) // 2
    hub = hub_index(inputs.root, y.shape[0])
    tau = 0.0
    kind = inputs.kind
    if prescribed(kind):
        th, thd, thdd = shaped_motion(kind, t, inputs.mp, inputs.shaper)
        y[hub] = th
        v[hub] = thd
        a[hub] = thdd
    if not inputs.traits.keeps_axial:
        for i in range(n):
            y[1 + i] = 0.0
            v[1 + i] = 0.0
            a[1 + i] = 0.0
    if not prescribed(kind):
        tau = free_hub_torque(inputs.drive, kind, t, y, v, inputs.mp, inputs.shaper, hub)
    return tau


@borrowing_kernel
def cholesky_factor(A):
    """Overwrite the lower triangle of a small SPD matrix with its Cholesky factor ``C``, the
    diagonal holding ``1 / C_jj`` (the solve then multiplies where it would divide, which takes
    the division latency off its chain of dependent operations).

    Returns False (and leaves ``A`` partly factored) if ``A`` is not positive definite.
    """
    N = A.shape[0]
    for j in range(N):
        d = A[j, j]
        for k in range(j):
            d -= A[j, k] * A[j, k]
        if not d > 0.0:
            return False
        inv = 1.0 / np.sqrt(d)
        A[j, j] = inv
        for i in range(j + 1, N):
            s = A[i, j]
            for k in range(j):
                s -= A[i, k] * A[j, k]
            A[i, j] = s * inv
    return True


@borrowing_kernel
def cholesky_solve(C, b):
    """Solve ``C C^T x = b`` in place, ``C`` from :func:`cholesky_factor` (reciprocal diagonal)."""
    N = C.shape[0]
    for i in range(N):
        s = b[i]
        for k in range(i):
            s -= C[i, k] * b[k]
        b[i] = s * C[i, i]
    for i in range(N - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, N):
            s -= C[k, i] * b[k]
        b[i] = s * C[i, i]


@borrowing_kernel
def solve_spd(A, b):
    """Solve A x = b in place (b <- x) for a small SPD ``A`` (overwritten by its factor)."""
    if not cholesky_factor(A):
        return False
    cholesky_solve(A, b)
    return True


#: Work arrays of the acceleration kernels, allocated once per simulation by :func:`workspace`:
#: the full mass matrix and force, the free block and its right-hand side, the free mask, and the
#: rows a compliant root's terms pass through (``hubbeam.core.root.add_joint``).
Workspace = namedtuple("Workspace", "M F Mff rhs is_free joint")


@kernel
def sized_workspace(N, n, free):
    """Allocate the :data:`Workspace` of ``N`` coordinates, ``n`` modes and free coordinates
    ``free``."""
    nf = free.shape[0]
    is_free = np.zeros(N, dtype=np.bool_)
    for i in range(nf):
        is_free[free[i]] = True
    return Workspace(np.empty((N, N)), np.empty(N), np.empty((nf, nf)), np.empty(nf), is_free,
                     np.empty((2, 2 * n)))


@kernel
def workspace(sm, free):
    """Allocate the :data:`Workspace` of a simulation with free coordinates ``free`` of ``y =
    (theta, q1, q2)``."""
    n = sm.M1.shape[0]
    return sized_workspace(1 + 2 * n, n, free)


@kernel
def inputs_workspace(inputs, free):
    """Allocate the :data:`Workspace` of the simulation ``inputs`` (with a compliant root, of
    ``y = (theta, q1, q2, phi)``)."""
    return sized_workspace(coordinate_count(inputs), inputs.sm.M1.shape[0], free)


@kernel
def equations(inputs, y, v, tau, ws):
    """The mass matrix and force of the simulation ``inputs`` into ``ws.M``, ``ws.F``, at the
    state ``(y, v)`` under the hub torque ``tau``, with the damping forces: the model's
    (:func:`mass_matrix_and_force`), or with a compliant root the link's about its hinge with the
    hinge, the spring and the damper (``hubbeam.core.root.add_joint``), the torque on the hub angle."""
    if has_joint(inputs.root):
        mass_matrix_and_force(inputs.traits, y, v, 0.0, inputs.sm, ws.M, ws.F)
        add_joint(inputs.traits, inputs.root, y, v, tau, ws.M, ws.F, ws.joint)
    else:
        mass_matrix_and_force(inputs.traits, y, v, tau, inputs.sm, ws.M, ws.F)
    add_damping(inputs.C, v, ws.F)


@borrowing_kernel
def solve_free(kind, tau, free, a_out, ws, hub):
    """Solve ``M_ff a_f = F_f - M_fc a_c`` from ``ws.M`` and ``ws.F`` (Eq. 24, already built),
    with the constrained ``a_c`` already in ``a_out``; returns ``(torque, F_theta - tau)``, the
    torque of a prescribed hub from its row ``hub`` (0, or a compliant root's hub angle)."""
    M = ws.M
    F = ws.F
    N = M.shape[0]
    Mff = ws.Mff
    rhs = ws.rhs
    nf = free.shape[0]
    for i in range(nf):
        fi = free[i]
        r = F[fi]
        for j in range(N):
            if not ws.is_free[j]:
                r -= M[fi, j] * a_out[j]
        rhs[i] = r
        for j in range(nf):
            Mff[i, j] = M[fi, free[j]]
    if not solve_spd(Mff, rhs):
        for i in range(nf):
            rhs[i] = np.nan
    for i in range(nf):
        a_out[free[i]] = rhs[i]
    q_theta = F[0] - tau
    if prescribed(kind):
        ma = 0.0
        for j in range(N):
            ma += M[hub, j] * a_out[j]
        tau = ma - (F[hub] - tau)
    return tau, q_theta


@borrowing_kernel
def solve_hub(inputs, tau, y, v, free, a_out, ws):
    """:func:`solve_free` of the simulation ``inputs`` at the state ``(y, v)``, whose mass matrix and
    force are in ``ws`` (hub torque ``tau``): ``(torque, Q_theta)`` with the torque of the hub's row
    (theta's, or with a compliant root the hub angle's) and, with a compliant root, ``Q_theta`` the
    root angle's force besides the spring's and the damper's torque."""
    torque, q_theta = solve_free(inputs.kind, tau, free, a_out, ws, hub_index(inputs.root, y.shape[0]))
    if has_joint(inputs.root):
        q_theta = ws.F[0] - spring_torque(inputs.root, y, v)
    return torque, q_theta


@kernel
def accelerations(inputs, t, y, v, free, a_out):
    """Accelerations of every coordinate at time ``t``; returns ``(torque, Q_theta)``.

    ``inputs``: :class:`~hubbeam.core.inputs.SimulationInputs` (its ``C`` holds the damping
    matrices of the elastic coordinates, :func:`add_damping`). ``y`` and ``v`` are full-length;
    their constrained entries are overwritten from the maneuver.
    The free accelerations solve ``M_ff a_f = F_f - M_fc a_c`` with the constrained accelerations
    ``a_c`` known. ``torque`` is the applied torque of a free hub, or the torque a prescribed motion
    requires, ``(M a)_theta - Q_theta`` (the hub row of Eq. 24). SFOAM has no Q_theta (zero). With
    a compliant root (``hubbeam.core.root``) the torque is the hub angle's and ``Q_theta`` the force
    on the root angle besides the spring's and the damper's torque.
    """
    ws = inputs_workspace(inputs, free)
    tau = impose_constraints(inputs, t, y, v, a_out)
    equations(inputs, y, v, tau, ws)
    return solve_hub(inputs, tau, y, v, free, a_out, ws)


@borrowing_kernel
def strain_energy(y, K1, K2):
    """The strain energy U = (q1^T K1 q1 + q2^T K2 q2) / 2 of Eq. (22) (the stiffness matrices
    passed alone: a call that passes the whole ``SystemMatrices`` costs more than this sum)."""
    n = K1.shape[0]
    return 0.5 * (_quad(K1, y, y, n, 1, 1) + _quad(K2, y, y, n, 1 + n, 1 + n))


@borrowing_kernel
def add_kinetic(M, v, e, hub):
    """``e`` plus the kinetic energy ``v^T M v / 2``, and the angular momentum about the hub axis: the
    momenta ``(M v)_0`` of theta and, with a compliant root, ``(M v)_hub`` of the hub angle (``hub`` 0
    without one, counted once)."""
    p = 0.0
    for i in range(v.shape[0]):
        mv = 0.0
        for j in range(v.shape[0]):
            mv += M[i, j] * v[j]
        e += 0.5 * v[i] * mv
        if i == 0 or i == hub:
            p += mv
    return e, p


@borrowing_kernel
def outputs(inputs, tau, y, v, free, a_out, ws):
    """Accelerations and ``(torque, Q_theta, energy, angular_momentum)`` of a state of the simulation
    ``inputs`` whose mass matrix and force are already in ``ws.M``, ``ws.F`` (applied torque
    ``tau``, constrained entries of ``y, v, a_out`` imposed): one mass matrix for all of them
    (:func:`solve_hub`, :func:`add_kinetic`). With a compliant root the torque is the hub angle's,
    the energy includes the spring's and the angular momentum about the hub axis is that of hub and
    link (the hub angle's and the root angle's momenta)."""
    torque, q_theta = solve_hub(inputs, tau, y, v, free, a_out, ws)
    energy = strain_energy(y, inputs.sm.K1, inputs.sm.K2)
    if has_joint(inputs.root):
        energy += spring_energy(inputs.root, y)
    e, p = add_kinetic(ws.M, v, energy, hub_index(inputs.root, y.shape[0]))
    return torque, q_theta, e, p


@borrowing_kernel
def joint_dissipation(inputs, v):
    """The power dissipated in the elastic coordinates and, with a compliant root, in its damper."""
    power = dissipation_rate(inputs.C, v)
    if has_joint(inputs.root):
        power += damper_power(inputs.root, v)
    return power


@kernel
def energy(traits, y, v, sm):
    """Total mechanical energy T + U, with T = y'^T M(y) y' / 2 and U of Eq. (22)."""
    N = y.shape[0]
    M = np.empty((N, N))
    F = np.empty(N)
    mass_matrix_and_force(traits, y, v, 0.0, sm, M, F)
    e = strain_energy(y, sm.K1, sm.K2)
    for i in range(N):
        for j in range(N):
            e += 0.5 * v[i] * M[i, j] * v[j]
    return e


@kernel
def angular_momentum(traits, y, v, sm):
    """Angular momentum about the hub axis, p_theta = dT/d(theta_dot) = (M(y) y')_theta."""
    N = y.shape[0]
    M = np.empty((N, N))
    F = np.empty(N)
    mass_matrix_and_force(traits, y, v, 0.0, sm, M, F)
    p = 0.0
    for j in range(N):
        p += M[0, j] * v[j]
    return p


@borrowing_kernel
def tip_outputs(y, sm):
    """Tip deflection v(L) = f2(L) q2, pure axial w1(L) = f1(L) q1 and wc(L) = -q2^T S(L) q2 / 2."""
    n = sm.f1L.shape[0]
    transverse = 0.0
    axial = 0.0
    for i in range(n):
        transverse += sm.f2L[i] * y[1 + n + i]
        axial += sm.f1L[i] * y[1 + i]
    foreshortening = -0.5 * _quad(sm.SL, y, y, n, 1 + n, 1 + n)
    return transverse, axial, foreshortening


@borrowing_kernel
def body_outputs(y, sm):
    """Displacement of the tip body's centre, the last point of the cloud (``docs/tip-body.md``):
    transverse ``(f2(l) + e f2'(l)) q2`` and axial ``f1(l) q1 - q2^T (S(l) + e f2'(l)^T f2'(l)) q2
    / 2``; the beam tip's values (:func:`tip_outputs`) for no tip mass."""
    n = sm.f1L.shape[0]
    k = sm.x.shape[0] - 1
    transverse = 0.0
    axial = 0.0
    for i in range(n):
        transverse += sm.F2[k, i] * y[1 + n + i]
        axial += sm.F1[k, i] * y[1 + i]
    return transverse, axial - 0.5 * _quad(sm.S[k], y, y, n, 1 + n, 1 + n)


@borrowing_kernel
def high_order_terms(Mc, Fc, tau, state, inputs, Mf, Ff, dQ):
    """The CFOAM terms FOAM drops (Eqs. 35-39, re-derived), along a state ``(y, v, a)`` with
    accelerations ``a``.

    ``Mc, Fc`` are CFOAM's mass matrix and force at ``(y, v)`` with applied torque ``tau`` and the
    damping forces of ``inputs.C``; ``Mf, Ff`` are overwritten with FOAM's, the first-order
    equations of the same traits (:func:`foam_system`; same damping, so it cancels).
    Writes ``dQ = (F_C - M_C a) - (F_F - M_F a)``: the generalised force the high-order terms add
    to FOAM's equations (theta, q1, q2 rows; accelerations moved to the right-hand side as in
    Eqs. 38-39) and returns
    ``Delta M_thth = M_C[0,0] - M_F[0,0]`` (Eq. 35). With a compliant root the state is that of
    ``(theta, q1, q2, phi)`` and ``Mc, Fc, Mf, Ff`` the link's equations about its hinge (the hinge's
    terms, the same in both models, cancel).
    """
    y, v, a = state
    N = Mf.shape[0]
    foam_system(inputs.traits, y, v, tau, inputs.sm, Mf, Ff)
    add_damping(inputs.C, v, Ff)
    for i in range(N):
        s = Fc[i] - Ff[i]
        for j in range(N):
            s -= (Mc[i, j] - Mf[i, j]) * a[j]
        dQ[i] = s
    return Mc[0, 0] - Mf[0, 0]
