"""CFOAM's mass matrix and force from point-cloud sums contracted once per simulation.

:func:`hubbeam.core.eom._cfoam_system` evaluates Lagrange's equations of the exact kinetic energy
(Eqs. 8-9; the high-order terms of Eqs. 35-39 re-derived in ``docs/cfoam.md``) by summing over the
point cloud ``k`` (weights ``w``, abscissae ``x``, ``r = rA + x``, rows ``f1 = F1[k]``,
``f2 = F2[k]``, symmetric ``S = S[k]``) at every call. Every sum is a polynomial in
``(q1, q2, q1', q2', thd)``, so :func:`cfoam_tensors` takes the sums once and :func:`cfoam_system`
only contracts them with the state.

Derivation. Per point, with ``a = f1 q1``, ``c = q2^T S q2 / 2``, ``s = S q2``, ``e = q2^T S q2'``,
``g = q2'^T S q2'``:

    X = r + a - c,  Y = f2 q2,  X' = f1 q1' - e,  Y' = f2 q2'
    bx = -g - 2 thd Y' - thd^2 X,   by = 2 thd X' - thd^2 Y
    X by - Y bx = 2 thd (X X' + Y Y') + Y g

The sums ``sum_k w_k (.)`` that occur define the tensors (``S`` symmetric, so every tensor with a
pair ``(a, b)`` of S-indices is symmetric in it):

    Jb = sum w r^2,  V1 = sum w r f1,  V2 = sum w r f2                        (order 0, 1)
    M1c = sum w f1 f1^T,  M2c = sum w f2 f2^T,  R = sum w f1 f2^T,  D = sum w r S   (order 2)
    A1[i,a,b] = sum w f1_i S_ab,   A2[i,a,b] = sum w f2_i S_ab                (order 3)
    T4[i,a,j,b] = sum w S_ia S_jb                                              (order 4)

Contracting the state into them gives the configuration matrices of the kernel

    B1[i,a] = (A1[i] q2)_a = sum w f1_i s_a,      C2[i,a] = (A2[i] q2)_a = sum w f2_i s_a
    W[i,j] = sum_ab T4[i,a,j,b] q2_a q2_b = sum w s_i s_j
    G[i,a] = sum_cd T4[i,a,c,d] q2'_c q2'_d = sum w S_ia g

and with them every entry of ``M = Jh e e^T + sum w J^T J`` and ``F = tau e - K y - sum w J^T b``:

    M_thth    = Jh + Jb + 2 V1.q1 + q1^T M1c q1 - q2^T D q2 + q2^T M2c q2
                - q1^T B1 q2 + q2^T W q2 / 4
    M_thq1    = -R q2
    M_thq2    = V2 + R^T q1 + C2^T q2 - (q2^T A2[i] q2)_i / 2 = V2 + R^T q1 + C2^T q2 - C2 q2 / 2
    M_q1q2    = -B1,   M_q1q1 = M1,   M_q2q2 = M2 + W
    F_th      = tau - 2 thd sum w (X X' + Y Y') - sum w Y g, where
      sum w (X X' + Y Y') = V1.q1' - q2^T D q2' + q1^T M1c q1' + q2^T M2c q2'
                            - q1^T B1 q2' - q1'^T B1 q2 / 2 + q2^T W q2' / 2
      sum w Y g           = sum_i q2_i (q2'^T A2[i] q2')
    F_q1[i]   = (q2'^T A1[i] q2') + 2 thd (R q2')_i + thd^2 (V1 + M1c q1 - B1 q2 / 2)_i - (K1 q1)_i
    F_q2[i]   = -2 thd (R^T q1' - C2 q2')_i + thd^2 (M2c q2)_i - (G q2)_i - 2 thd (C2^T q2')_i
                - thd^2 (D q2 + B1^T q1 - W q2 / 2)_i - (K2 q2)_i

(``M1, M2, K1, K2, Jh`` are the :class:`~hubbeam.model.matrices.SystemMatrices` fields the point-cloud
kernel uses directly; ``M1c, M2c`` are their point-cloud sums, equal to them up to rounding.)

A tip body's rotary inertia ``Jt`` (``docs/tip-body.md``, ``g = f2'(l)``) adds the constant
``Jt``, ``Jt g`` and ``Jt g^T g`` to ``M_thth``, ``M_thq2`` and ``M_q2q2`` and nothing to the force:
:func:`cfoam_tensors` folds them into ``Jb``, ``V2`` and ``M2`` (each used only there).

Symmetry. ``W`` and ``G`` are symmetric, and so are the quadratic forms in ``q2`` and ``q2'``, so
the 4-index work runs over packed pairs ``p = (a <= b)``, ``m = n (n + 1) / 2`` of them: with
``Q_p = q2_a q2_b`` and ``U_p = q2'_a q2'_b`` (doubled for ``a < b``),

    W[p(i,j)] = sum_p TW[p(i,j), p] Q_p,   TW[(i,j),(a,b)] = (T4[i,a,j,b] + T4[i,b,j,a]) / 2
    G[p(i,a)] = sum_p TG[p(i,a), p] U_p,   TG[(i,a),(c,d)] = T4[i,a,c,d]

(``2 m^2`` products instead of ``2 n^4``), and ``q2'^T A[i] q2'`` is ``sum_p A[i, p] U_p``.
``TW`` and ``TG`` are symmetric matrices over pairs, so the kernel sums their rows
(``W += TW[p] Q_p``): the inner loop then has independent sums, which the compiler vectorises
without reordering any sum. ``B1`` and ``C2`` are written straight into ``M`` and ``F``; only
``Q, U, W, G`` (packed) are kept, in the scratch ``work``.

Cost per call ``2 m^2 + 2 n^3 + 2 n m + O(n^2)`` multiply-adds against about ``3.5 n^2`` per point
(65 points for up to 11 modes) for the point cloud: measured 9x faster for 5 modes, 4x for 10 and
still about 2x for 20.
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.jit import borrowing_kernel, kernel

#: Pre-contracted point-cloud sums of CFOAM (see the module docstring), built by
#: :func:`cfoam_tensors`:
#:
#: * ``Jh``: hub inertia; ``Jb``: ``sum w (rA + x)^2 + Jt``;
#: * ``vecs`` (2, n): ``V1``, ``V2 + Jt g``;
#: * ``mats`` (8, n, n): ``M1, M2 + Jt g^T g, K1, K2`` (from SystemMatrices), ``M1c, M2c, R, D``
#:   (sums);
#: * ``A`` (2, n, n, n): ``A1, A2``;
#: * ``T`` (2, m, m): ``TW, TG`` over packed pairs;
#: * ``work`` (4, m): scratch for ``Q, U, W, G`` (packed) of the state, overwritten by every call of
#:   :func:`cfoam_system`: one CfoamTensors per simulation, never shared between threads.
CfoamTensors = namedtuple("CfoamTensors", "Jh Jb vecs mats A T work")

# slices of CfoamTensors.mats
_M1, _M2, _K1, _K2, _M1C, _M2C, _R, _D = range(8)


@kernel
def cfoam_tensors(sm):
    """The :data:`CfoamTensors` of the :class:`~hubbeam.model.matrices.SystemMatrices` ``sm``.

    Contracts the point cloud ``(sm.x, sm.w, sm.F1, sm.F2, sm.S)`` into the tensors of the module
    docstring. Every ``S(x_k)`` of Eq. (20) must be symmetric (``hubbeam.model.matrices`` makes it so
    exactly); the tensors use its symmetric part.
    """
    n = sm.M1.shape[0]
    m = n * (n + 1) // 2
    for k in range(sm.x.shape[0]):
        for a in range(n):
            for b in range(a + 1, n):
                if abs(sm.S[k, a, b] - sm.S[k, b, a]) > 1e-12 * (abs(sm.S[k, a, b])
                                                                 + abs(sm.S[k, b, a])):
                    raise ValueError("SystemMatrices.S: S(x_k) of Eq. (20) is not symmetric at "
                                     "some point; allowed: symmetric matrices")
    vecs = np.zeros((2, n))
    mats = np.zeros((8, n, n))
    A = np.zeros((2, n, n, n))
    T = np.zeros((2, m, m))
    S = np.empty((n, n))
    Jb = 0.0
    for i in range(n):
        for j in range(n):
            mats[_M1, i, j] = sm.M1[i, j]
            mats[_M2, i, j] = sm.M2[i, j]
            mats[_K1, i, j] = sm.K1[i, j]
            mats[_K2, i, j] = sm.K2[i, j]
    for k in range(sm.x.shape[0]):
        wk = sm.w[k]
        if wk == 0.0:
            continue
        r = sm.rA + sm.x[k]
        for a in range(n):
            for b in range(n):
                S[a, b] = 0.5 * (sm.S[k, a, b] + sm.S[k, b, a])
        Jb += wk * r * r
        for i in range(n):
            f1 = wk * sm.F1[k, i]
            f2 = wk * sm.F2[k, i]
            vecs[0, i] += r * f1
            vecs[1, i] += r * f2
            for j in range(n):
                mats[_M1C, i, j] += f1 * sm.F1[k, j]
                mats[_M2C, i, j] += f2 * sm.F2[k, j]
                mats[_R, i, j] += f1 * sm.F2[k, j]
                mats[_D, i, j] += wk * r * S[i, j]
                for b in range(n):
                    A[0, i, j, b] += f1 * S[j, b]
                    A[1, i, j, b] += f2 * S[j, b]
        po = 0
        for i in range(n):
            for j in range(i, n):
                p = 0
                for a in range(n):
                    for b in range(a, n):
                        T[0, po, p] += 0.5 * wk * (S[i, a] * S[j, b] + S[i, b] * S[j, a])
                        T[1, po, p] += wk * S[i, j] * S[a, b]
                        p += 1
                po += 1
    if sm.Jt != 0.0:  # the tip body's rotary inertia (module docstring)
        Jb += sm.Jt
        for i in range(n):
            vecs[1, i] += sm.Jt * sm.dF2t[i]
            for j in range(n):
                mats[_M2, i, j] += sm.Jt * sm.dF2t[i] * sm.dF2t[j]
    return CfoamTensors(float(sm.Jh), Jb, vecs, mats, A, T, np.empty((4, m)))


@borrowing_kernel
def cfoam_system(y, v, tau, ct, M, F):
    """Mass matrix ``M(y)`` and force ``F(y, y')`` of CFOAM from the tensors ``ct``.

    The same ``M`` (full ``N x N``) and ``F`` (``F_theta = tau + Q_theta``) as
    :func:`hubbeam.core.eom._cfoam_system`: Lagrange's equations of the exact kinetic energy
    (Eqs. 8-9), which keep every high-order term of Eqs. (35)-(39) (``docs/cfoam.md``); the
    formulae are in the module docstring. Allocates nothing (``ct.work`` is overwritten).
    """
    n = ct.vecs.shape[1]
    o1 = 1
    o2 = 1 + n
    thd = v[0]
    thd2 = thd * thd
    mats = ct.mats
    A = ct.A
    T = ct.T
    work = ct.work

    # packed products Q_p = q2_a q2_b, U_p = q2'_a q2'_b (a <= b, doubled off the diagonal)
    p = 0
    for a in range(n):
        qa = y[o2 + a]
        ua = v[o2 + a]
        work[0, p] = qa * qa
        work[1, p] = ua * ua
        p += 1
        for b in range(a + 1, n):
            work[0, p] = 2.0 * qa * y[o2 + b]
            work[1, p] = 2.0 * ua * v[o2 + b]
            p += 1

    # orders 0 to 2: vectors and matrices
    m00 = ct.Jh + ct.Jb
    xx = 0.0  # sum w (X X' + Y Y')
    yg = 0.0  # sum w Y g
    for i in range(n):
        m1q1 = 0.0
        m1u1 = 0.0
        m2q2 = 0.0
        m2u2 = 0.0
        rq2 = 0.0
        ru2 = 0.0
        rtq1 = 0.0
        rtu1 = 0.0
        dq2 = 0.0
        du2 = 0.0
        k1q1 = 0.0
        k2q2 = 0.0
        for j in range(n):
            q1j = y[o1 + j]
            q2j = y[o2 + j]
            u1j = v[o1 + j]
            u2j = v[o2 + j]
            m1q1 += mats[_M1C, i, j] * q1j
            m1u1 += mats[_M1C, i, j] * u1j
            m2q2 += mats[_M2C, i, j] * q2j
            m2u2 += mats[_M2C, i, j] * u2j
            rq2 += mats[_R, i, j] * q2j
            ru2 += mats[_R, i, j] * u2j
            rtq1 += mats[_R, j, i] * q1j
            rtu1 += mats[_R, j, i] * u1j
            dq2 += mats[_D, i, j] * q2j
            du2 += mats[_D, i, j] * u2j
            k1q1 += mats[_K1, i, j] * q1j
            k2q2 += mats[_K2, i, j] * q2j
            M[o1 + i, o1 + j] = mats[_M1, i, j]
        q1i = y[o1 + i]
        q2i = y[o2 + i]
        m00 += q1i * (2.0 * ct.vecs[0, i] + m1q1) + q2i * (m2q2 - dq2)
        xx += ct.vecs[0, i] * v[o1 + i] + q1i * m1u1 + q2i * (m2u2 - du2)
        M[0, o1 + i] = -rq2
        M[0, o2 + i] = ct.vecs[1, i] + rtq1
        F[o1 + i] = 2.0 * thd * ru2 + thd2 * (ct.vecs[0, i] + m1q1) - k1q1
        F[o2 + i] = -2.0 * thd * rtu1 + thd2 * (m2q2 - dq2) - k2q2

    # order 3: B1 = A1 q2 and C2 = A2 q2 row by row, quadratic forms q2'^T A[i] q2'
    for i in range(n):
        q1i = y[o1 + i]
        q2i = y[o2 + i]
        u2i = v[o2 + i]
        b1q = 0.0
        b1u = 0.0
        c2q = 0.0
        c2u = 0.0
        for a in range(n):
            b1 = 0.0
            c2 = 0.0
            for b in range(n):
                b1 += A[0, i, a, b] * y[o2 + b]
                c2 += A[1, i, a, b] * y[o2 + b]
            M[o1 + i, o2 + a] = -b1
            M[o2 + a, o1 + i] = -b1
            M[0, o2 + a] += q2i * c2
            F[o2 + a] -= thd2 * q1i * b1 + 2.0 * thd * u2i * c2
            b1q += b1 * y[o2 + a]
            b1u += b1 * v[o2 + a]
            c2q += c2 * y[o2 + a]
            c2u += c2 * v[o2 + a]
        a1uu = 0.0
        a2uu = 0.0
        p = 0
        for a in range(n):
            for b in range(a, n):
                a1uu += A[0, i, a, b] * work[1, p]
                a2uu += A[1, i, a, b] * work[1, p]
                p += 1
        m00 -= q1i * b1q
        xx -= q1i * b1u + 0.5 * v[o1 + i] * b1q
        yg += q2i * a2uu
        M[0, o2 + i] -= 0.5 * c2q
        F[o1 + i] += a1uu - 0.5 * thd2 * b1q
        F[o2 + i] += 2.0 * thd * c2u

    # order 4: W and G over packed pairs, accumulated column by column (TW, TG symmetric) so
    # that the inner loop has independent sums
    m = work.shape[1]
    for po in range(m):
        work[2, po] = 0.0
        work[3, po] = 0.0
    for p in range(m):
        qp = work[0, p]
        up = work[1, p]
        for po in range(m):
            work[2, po] += T[0, p, po] * qp
            work[3, po] += T[1, p, po] * up
    qwq = 0.0
    qwu = 0.0
    po = 0
    for i in range(n):
        for j in range(i, n):
            wij = work[2, po]
            M[o2 + i, o2 + j] = mats[_M2, i, j] + wij
            M[o2 + j, o2 + i] = M[o2 + i, o2 + j]
            f = 0.5 * thd2 * wij - work[3, po]
            qwq += wij * work[0, po]
            if i == j:
                F[o2 + i] += f * y[o2 + i]
                qwu += wij * y[o2 + i] * v[o2 + i]
            else:
                F[o2 + i] += f * y[o2 + j]
                F[o2 + j] += f * y[o2 + i]
                qwu += wij * (y[o2 + i] * v[o2 + j] + y[o2 + j] * v[o2 + i])
            po += 1

    M[0, 0] = m00 + 0.25 * qwq
    for i in range(n):
        M[o1 + i, 0] = M[0, o1 + i]
        M[o2 + i, 0] = M[0, o2 + i]
    xx += 0.5 * qwu
    F[0] = tau - 2.0 * thd * xx - yg
