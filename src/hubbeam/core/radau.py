"""Radau IIA of order 5 for second-order systems ``y'' = a(t, y, y')``, as numba kernels.

The method (Hairer & Wanner, *Solving Ordinary Differential Equations II*, Sec. IV.8) is the
3-stage collocation method at the right Radau points: order 5, L-stable and stiffly accurate, so
the stiff axial modes of the hub-beam are damped instead of resolved. The kernels integrate the
first-order system ``z = (y, v)``, ``z' = f(t, z) = (v, a(t, y, v))`` of ``N`` free coordinates.

Stage equations and the simplified Newton iteration
    The stage increments ``Z_i = z(t0 + c_i h) - z0`` satisfy ``Z = h (A kron I) F(Z)``. With a
    Jacobian approximation ``J = [[0, I], [Ka, Ca]]`` (``Ka = da/dy``, ``Ca = da/dv`` by forward
    differences, kept over steps while Newton converges fast) the Newton matrix
    ``(A^-1 / h) kron I - I kron J`` is block-diagonalised by ``W = (T^-1 kron I) Z``, in which
    ``A^-1`` becomes ``diag(gamma, [[alpha, beta], [-beta, alpha]])``: one real system with
    ``gamma/h - J`` and one complex system with ``(alpha - i beta)/h - J`` per iteration.

Second-order reduction
    For ``J = [[0, I], [Ka, Ca]]`` the system ``(mu I - J) (dy, dv) = (ry, rv)`` is solved as
    ``(mu^2 I - mu Ca - Ka) dy = rv + (mu I - Ca) ry``, ``dv = mu dy - ry``: every LU factorisation
    is ``N x N`` instead of ``2N x 2N``. Factors are reused while ``h`` and ``J`` are unchanged.

Error control
    The embedded order-3 solution ``y^ = y0 + h (gamma0 f(t0, z0) + sum b^_i F_i)``, ``gamma0 =
    1/gamma``, gives the estimate ``err = (gamma/h - J)^-1 (f(t0, z0) + (gamma/h) sum_j e_j Z_j)``
    (the filter ``(I - h gamma0 J)^-1`` keeps it bounded for stiff components). A step is accepted
    when the root-mean-square of ``err_k / (atol + rtol max(|z0_k|, |z1_k|))`` over all ``2N``
    components of ``z = (y, v)`` is at most 1; positions and velocities are controlled alike.
    The estimate is ``O(h^4)``, so the next step is
    ``h fac err^(-1/4)`` (``fac`` = 0.9, less after many Newton iterations), limited to
    ``[0.2, 8] h``, the smaller of this and Gustafsson's predictive controller after an accepted
    step, and ``h`` is kept unchanged when the ratio falls in ``[1, 1.2]`` so that the LU factors
    can be reused. The global error this gives is typically well below ``rtol`` (measured in the
    tests), as the order-5 solution is propagated while the order-3 estimate is controlled.

Dense output
    On each accepted step, positions on the output grid come from the quintic Hermite polynomial
    through ``(y, v, a)`` at both ends (``O(h^6)``), velocities from its derivative.

The right-hand side is attached to a problem type: :func:`register_rhs` declares
``rhs(t, y, v, a, problem)`` (a jitted function writing the accelerations ``a``) for every
``problem`` of a given namedtuple class; the kernels below are specialised on that class at
compile time (a direct call, no function pointer, so that the compiled kernels can be cached).
A problem class may also declare hooks (:func:`register_hooks`): one at each stop, which may
switch the problem's forcing there (the integration then restarts as at its start), and one after
every accepted step; a class without hooks compiles to the plain integrator.
"""

import math
from collections import namedtuple

import numpy as np
from numba.extending import overload

from hubbeam.core.jit import JIT_OPTIONS, borrowing_kernel, inline_kernel, internal_kernel, kernel
from hubbeam.core.step_control import INITIAL_STEP_FRACTION, MAX_FACTOR, MIN_FACTOR

# Status codes returned by :func:`radau5`, the one home of a run's status (the names are stored
# in the datasets as ``integrator_status`` and as the sweeps' flag meanings).
# Whether a stopped run diverged or left the range of the models is decided from these codes by
# ``hubbeam.model.validity``.
SUCCESS = 0         # reached the end time
LEFT_RANGE = 1      # the watched quantity (tip deflection) exceeded its limit
NON_FINITE = 2      # the state or the right-hand side became NaN or infinite
STEP_UNDERFLOW = 3  # the step size fell below the resolution of the time
TOO_MANY_STEPS = 4  # the budget of attempted steps was used up
STATUS_NAMES = ("success", "left_range", "non_finite", "step_underflow", "too_many_steps")

# Slots of the integer statistics array.
ACCEPTED = 0
REJECTED = 1
NEWTON_FAILURES = 2
RHS_CALLS = 3
JACOBIANS = 4
FACTORIZATIONS = 5
STAT_NAMES = ("n_steps", "n_rejected", "n_newton_failures", "n_rhs", "n_jacobian", "n_lu")

# Controller constants (dimensionless).
NEWTON_MAX_ITER = 7        # simplified Newton iterations per attempt
NEWTON_NOISE = 0.03        # scaled correction accepted when Newton stagnates (kappa of IV.8)
JACOBIAN_REFRESH = 0.03    # recompute J after a step whose Newton contraction rate exceeded this
KEEP_STEP_LOW = 1.0        # keep h (and the LU factors) when the proposed ratio is in [low, high]
KEEP_STEP_HIGH = 1.2
SAFETY = 0.9
SAME_STEP = 1e-12          # relative difference of a restart's step from the LU factors' step they reuse


def _radau_constants():
    """Radau IIA (s = 3) coefficients, derived from the collocation conditions.

    Returns ``c``, the eigen-transformation ``T`` with ``T^-1 A^-1 T = diag(gamma, [[alpha,
    beta], [-beta, alpha]])``, ``T^-1``, ``gamma, alpha, beta``, the error weights ``e`` and the
    quintic Hermite basis ``H[i, k]`` (coefficient of ``s^k`` of the basis function multiplying
    ``(y0, h v0, h^2 a0, y1, h v1, h^2 a1)[i]``).
    """
    s6 = math.sqrt(6.0)
    c = np.array([(4.0 - s6) / 10.0, (4.0 + s6) / 10.0, 1.0])
    k = np.arange(1, 4)
    vander = c[:, None] ** (k - 1)  # vander[j, k-1] = c_j^(k-1)
    # collocation conditions: sum_j A_ij c_j^(k-1) = c_i^k / k, k = 1, 2, 3
    A = np.linalg.solve(vander.T, (c[:, None] ** k / k).T).T
    A_inv = np.linalg.inv(A)
    lam, vec = np.linalg.eig(A_inv)
    i_real = int(np.argmin(np.abs(lam.imag)))
    i_cplx = int(np.argmax(lam.imag))
    gamma = float(lam[i_real].real)
    alpha, beta = float(lam[i_cplx].real), float(lam[i_cplx].imag)
    T = np.column_stack([vec[:, i_real].real, vec[:, i_cplx].real, vec[:, i_cplx].imag])
    # embedded order-3 weights b^ with b^_0 = 1/gamma on f(t0, z0): sum b^_j c_j^(k-1) = 1/k
    gamma0 = 1.0 / gamma
    b_hat = np.linalg.solve(vander.T, np.array([1.0 - gamma0, 0.5, 1.0 / 3.0]))
    e = (b_hat - A[2]) @ A_inv
    # quintic Hermite: rows = conditions p, p', p'' at s = 0 and s = 1, columns = powers s^k
    cond = np.zeros((6, 6))
    for side, s in ((0, 0.0), (3, 1.0)):
        for d in range(3):
            for kk in range(d, 6):
                cond[side + d, kk] = math.perm(kk, d) * s ** (kk - d)
    hermite = np.linalg.inv(cond).T
    return tuple(np.ascontiguousarray(x) for x in (c, A, T, np.linalg.inv(T), e, hermite)) + (
        gamma, alpha, beta)


C, A_RADAU, T_RADAU, T_INV_RADAU, E_ERR, HERMITE, GAMMA, ALPHA, BETA = _radau_constants()
ROWSUM_T_INV = np.ascontiguousarray(T_INV_RADAU.sum(axis=1))
UROUND = float(np.finfo(np.float64).eps)


# --------------------------------------------------------------------------- the problem
_RHS_REGISTRY = {}


def register_rhs(problem_class, rhs):
    """Declare the jitted ``rhs(t, y, v, a, problem)`` for problems of the namedtuple class.

    ``rhs`` writes ``a = y''`` (length ``N``) at time ``t`` for positions ``y`` and velocities
    ``v`` of the integrated coordinates; ``problem`` carries its parameters and work arrays.
    """
    if not (isinstance(problem_class, type) and issubclass(problem_class, tuple)
            and hasattr(problem_class, "_fields")):
        raise TypeError(f"problem_class = {problem_class!r}: expected a namedtuple class")
    _RHS_REGISTRY[problem_class] = rhs


def registered_rhs(problem_class):
    """The ``rhs`` declared for ``problem_class`` by :func:`register_rhs`."""
    try:
        return _RHS_REGISTRY[problem_class]
    except KeyError:
        raise TypeError(f"no right-hand side is registered for {problem_class!r}") from None


def problem_rhs(t, y, v, a, problem):
    """``a = y''(t, y, v)`` of ``problem``: the registered ``rhs`` (see :func:`register_rhs`);
    inside jitted code the call is resolved at compile time."""
    registered_rhs(type(problem))(t, y, v, a, problem)


@overload(problem_rhs, jit_options=JIT_OPTIONS, inline="always")
def _problem_rhs_overload(t, y, v, a, problem):
    rhs = _RHS_REGISTRY.get(getattr(problem, "instance_class", None))
    if rhs is None:
        return None

    def impl(t, y, v, a, problem):
        rhs(t, y, v, a, problem)

    return impl


# --------------------------------------------------------------------------- hooks
_HOOK_REGISTRY = {}


def register_hooks(problem_class, at_stop, after_step):
    """Declare the jitted hooks of the namedtuple class ``problem_class`` (after its ``rhs``).

    ``at_stop(t, y, v, problem)`` runs at the start and at every stop of ``t_stops`` that an
    accepted step lands on (the state is there); it returns True when the problem's forcing jumps
    at ``t`` (a sampled controller's new input), and :func:`radau5` then restarts from ``(t, y,
    v)``: the accelerations are evaluated anew, the next step starts from zero stage values, its
    error estimate is refined as at a start and the step-size controller forgets the previous
    step (the Jacobian and the LU factors are kept: the forcing does not enter them).
    ``after_step(t, h, start, end, problem)`` runs after every accepted step from ``t`` to ``t +
    h`` with ``start = (y0, v0, a0)`` and ``end = (y1, v1, a1)``, the data of the dense output
    (quantities integrated along the solution). Problems of other classes have no hooks.
    """
    registered_rhs(problem_class)
    _HOOK_REGISTRY[problem_class] = (at_stop, after_step)


def at_stop(t, y, v, problem):
    """The ``at_stop`` hook of ``problem`` (:func:`register_hooks`); False without one."""
    hooks = _HOOK_REGISTRY.get(type(problem))
    return hooks is not None and hooks[0](t, y, v, problem)


def after_step(t, h, start, end, problem):
    """The ``after_step`` hook of ``problem`` (:func:`register_hooks`); nothing without one."""
    hooks = _HOOK_REGISTRY.get(type(problem))
    if hooks is not None:
        hooks[1](t, h, start, end, problem)


@overload(at_stop, jit_options=JIT_OPTIONS, inline="always")
def _at_stop_overload(t, y, v, problem):
    hooks = _HOOK_REGISTRY.get(getattr(problem, "instance_class", None))
    if hooks is None:
        def impl(t, y, v, problem):
            return False
        return impl
    hook = hooks[0]

    def impl(t, y, v, problem):
        return hook(t, y, v, problem)

    return impl


@overload(after_step, jit_options=JIT_OPTIONS, inline="always")
def _after_step_overload(t, h, start, end, problem):
    hooks = _HOOK_REGISTRY.get(getattr(problem, "instance_class", None))
    if hooks is None:
        def impl(t, h, start, end, problem):
            return None
        return impl
    hook = hooks[1]

    def impl(t, h, start, end, problem):
        hook(t, h, start, end, problem)

    return impl


#: A validation problem with closed-form solutions, ``y'' = -K y - C y' + g cos(omega t)
#: + nonlinear * 2 y * y'`` (the last term componentwise; ``y = tan t`` solves ``y'' = 2 y y'``).
#: It lives in the package, not in the tests, so that every problem type a cached kernel is
#: compiled for can be imported wherever numba reads the cache index.
ForcedOscillator = namedtuple("ForcedOscillator", "K C g omega nonlinear")


# --------------------------------------------------------------------------- linear algebra
@inline_kernel
def _magnitude(x):
    """``|Re x| + |Im x|``: the pivot size LAPACK uses for complex matrices (no square root)."""
    return abs(x.real) + abs(x.imag)


@borrowing_kernel
def lu_factor(mat, piv):
    """In-place LU factorisation with partial pivoting (real or complex); False if singular.

    The unit lower factor is stored below the diagonal, the upper factor above it, and the
    diagonal holds the reciprocals of the pivots: :func:`lu_solve` then multiplies where it would
    divide, which takes the division latency off its chain of dependent operations.
    """
    n = mat.shape[0]
    for k in range(n):
        p = k
        big = _magnitude(mat[k, k])
        for i in range(k + 1, n):
            size = _magnitude(mat[i, k])
            if size > big:
                big = size
                p = i
        piv[k] = p
        if not (big > 0.0 and big < np.inf):
            return False
        if p != k:
            for j in range(n):
                tmp = mat[k, j]
                mat[k, j] = mat[p, j]
                mat[p, j] = tmp
        inv = 1.0 / mat[k, k]
        mat[k, k] = inv
        for i in range(k + 1, n):
            mat[i, k] *= inv
            f = mat[i, k]
            for j in range(k + 1, n):
                mat[i, j] -= f * mat[k, j]
    return True


@borrowing_kernel
def lu_solve(lu, piv, b):
    """Solve ``lu x = b`` in place for factors from :func:`lu_factor`."""
    n = lu.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= lu[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s * lu[i, i]


@internal_kernel
def _form_reduced(mu, Ka, Ca, mat):
    """``mat = mu^2 I - mu Ca - Ka``: ``mu I - J`` after eliminating the velocity block."""
    n = Ka.shape[0]
    for i in range(n):
        for j in range(n):
            mat[i, j] = -mu * Ca[i, j] - Ka[i, j]
        mat[i, i] += mu * mu


@internal_kernel
def _reduced_solve(lu, piv, mu, Ca, ry, rv, dy, dv):
    """Solve ``(mu I - J) (dy, dv) = (ry, rv)`` for ``J = [[0, I], [Ka, Ca]]``."""
    n = ry.shape[0]
    for i in range(n):
        s = rv[i] + mu * ry[i]
        for j in range(n):
            s -= Ca[i, j] * ry[j]
        dy[i] = s
    lu_solve(lu, piv, dy)
    for i in range(n):
        dv[i] = mu * dy[i] - ry[i]


@borrowing_kernel
def forced_oscillator_rhs(t, y, v, a, problem):
    """Right-hand side of :data:`ForcedOscillator`."""
    forcing = math.cos(problem.omega * t)
    K, C_damp, g = problem.K, problem.C, problem.g
    for i in range(y.shape[0]):
        s = g[i] * forcing + 2.0 * problem.nonlinear * y[i] * v[i]
        for j in range(y.shape[0]):
            s -= K[i, j] * y[j] + C_damp[i, j] * v[j]
        a[i] = s


register_rhs(ForcedOscillator, forced_oscillator_rhs)


# --------------------------------------------------------------------------- small helpers
@internal_kernel
def _all_finite(x):
    for i in range(x.shape[0]):
        if not np.isfinite(x[i]):
            return False
    return True


@internal_kernel
def _copy(src, dst):
    for i in range(src.shape[0]):
        dst[i] = src[i]


@internal_kernel
def _scale(y0, v0, y1, v1, rtol, atol, sc):
    """Reciprocal error weights ``1 / (atol + rtol max(|z0_k|, |z1_k|))`` of ``z = (y, v)``
    (the norms below multiply by them)."""
    n = y0.shape[0]
    for i in range(n):
        sc[i] = 1.0 / (atol + rtol * max(abs(y0[i]), abs(y1[i])))
        sc[n + i] = 1.0 / (atol + rtol * max(abs(v0[i]), abs(v1[i])))


@internal_kernel
def _rms(dy, dv, sc):
    """Weighted root-mean-square norm of ``(dy, dv)`` (NaN propagates)."""
    n = dy.shape[0]
    s = 0.0
    for i in range(n):
        s += (dy[i] * sc[i]) ** 2 + (dv[i] * sc[n + i]) ** 2
    return math.sqrt(s / (2 * n))


@internal_kernel
def _rms_stages(dy, dv, sc):
    """Weighted root-mean-square norm over the three stages of ``(dy, dv)``, shape (3, N)."""
    n = dy.shape[1]
    s = 0.0
    for k in range(3):
        for i in range(n):
            s += (dy[k, i] * sc[i]) ** 2 + (dv[k, i] * sc[n + i]) ** 2
    return math.sqrt(s / (6 * n))


Workspace = namedtuple(
    "Workspace",
    "a y1 v1 a1 Zy Zv Zy_acc Zv_acc Wy Wv Fa ry rv dWy dWv cy cv cdy cdv y_st v_st a_st ey ev "
    "Ka Ca lu_r piv_r lu_c piv_c sc ext",
)


@kernel
def workspace(n):
    """Every work array of an integration of ``N = n`` coordinates (allocated once)."""
    return Workspace(
        np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
        np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)),
        np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)),
        np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)),
        np.zeros(n, np.complex128), np.zeros(n, np.complex128),
        np.zeros(n, np.complex128), np.zeros(n, np.complex128),
        np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
        np.zeros((n, n)), np.zeros((n, n)),
        np.zeros((n, n)), np.zeros(n, np.int64),
        np.zeros((n, n), np.complex128), np.zeros(n, np.int64),
        np.zeros(2 * n), np.zeros((3, 3)),
    )


# --------------------------------------------------------------------------- building blocks
@internal_kernel
def _difference_column(problem, t, w, perturbed, j, out):
    """Column ``j`` of ``out = da/dx`` by a forward difference in ``perturbed[j]`` (``perturbed``
    is ``w.y_st`` or ``w.v_st``, restored afterwards); ``w.a`` holds ``a(t, w.y_st, w.v_st)``."""
    y_st, v_st, a, a_st = w.y_st, w.v_st, w.a, w.a_st
    x = perturbed[j]
    delta = math.sqrt(UROUND * max(1e-5, abs(x)))
    perturbed[j] = x + delta
    problem_rhs(t, y_st, v_st, a_st, problem)
    perturbed[j] = x
    for i in range(a.shape[0]):
        out[i, j] = (a_st[i] - a[i]) / delta


@borrowing_kernel
def jacobian(problem, t, y, v, w, stats):
    """Forward-difference ``w.Ka = da/dy`` and ``w.Ca = da/dv`` at ``(t, y, v)``; ``w.a`` must
    hold ``a(t, y, v)``. Costs ``2N`` right-hand-side calls."""
    n = y.shape[0]
    _copy(y, w.y_st)
    _copy(v, w.v_st)
    for j in range(n):
        _difference_column(problem, t, w, w.y_st, j, w.Ka)
        _difference_column(problem, t, w, w.v_st, j, w.Ca)
    stats[JACOBIANS] += 1
    stats[RHS_CALLS] += 2 * n


@internal_kernel
def _factorize(h, w, stats):
    """LU factors of the reduced real and complex Newton matrices for step ``h``."""
    _form_reduced(GAMMA / h, w.Ka, w.Ca, w.lu_r)
    _form_reduced(complex(ALPHA, -BETA) / h, w.Ka, w.Ca, w.lu_c)
    lu_factor(w.lu_r, w.piv_r)
    lu_factor(w.lu_c, w.piv_c)
    stats[FACTORIZATIONS] += 1


@internal_kernel
def _extrapolate_stages(ratio, w):
    """Starting values: the last accepted step's collocation polynomial, continued.

    The cubic ``P`` with ``P(0) = 0`` and ``P(c_j) = Z_j`` of the accepted step (``w.Zy_acc``,
    ``w.Zv_acc``) gives ``Z_i = P(1 + c_i ratio) - P(1)`` for a step ``ratio`` times as long.
    """
    ext, Zy, Zv, Zy_acc, Zv_acc = w.ext, w.Zy, w.Zv, w.Zy_acc, w.Zv_acc
    for i in range(3):
        tau = 1.0 + C[i] * ratio
        for j in range(3):
            lj = tau / C[j]
            for k in range(3):
                if k != j:
                    lj *= (tau - C[k]) / (C[j] - C[k])
            ext[i, j] = lj - (1.0 if j == 2 else 0.0)
    for i in range(3):
        e0, e1, e2 = ext[i, 0], ext[i, 1], ext[i, 2]
        for m in range(Zy.shape[1]):
            Zy[i, m] = e0 * Zy_acc[0, m] + e1 * Zy_acc[1, m] + e2 * Zy_acc[2, m]
            Zv[i, m] = e0 * Zv_acc[0, m] + e1 * Zv_acc[1, m] + e2 * Zv_acc[2, m]


@borrowing_kernel
def hermite_interpolate(s, h, start, end, y_out, v_out):
    """Quintic Hermite position and its derivative at ``t0 + s h`` from ``start = (y0, v0, a0)``
    and ``end = (y1, v1, a1)``, the ends of a step of size ``h``."""
    y0, v0, a0 = start
    y1, v1, a1 = end
    b0 = b1 = b2 = b3 = b4 = b5 = 0.0
    d0 = d1 = d2 = d3 = d4 = d5 = 0.0
    for k in range(5, -1, -1):
        b0 = b0 * s + HERMITE[0, k]
        b1 = b1 * s + HERMITE[1, k]
        b2 = b2 * s + HERMITE[2, k]
        b3 = b3 * s + HERMITE[3, k]
        b4 = b4 * s + HERMITE[4, k]
        b5 = b5 * s + HERMITE[5, k]
        if k > 0:
            d0 = d0 * s + k * HERMITE[0, k]
            d1 = d1 * s + k * HERMITE[1, k]
            d2 = d2 * s + k * HERMITE[2, k]
            d3 = d3 * s + k * HERMITE[3, k]
            d4 = d4 * s + k * HERMITE[4, k]
            d5 = d5 * s + k * HERMITE[5, k]
    for m in range(y0.shape[0]):
        y_out[m] = (b0 * y0[m] + b3 * y1[m] + h * (b1 * v0[m] + b4 * v1[m])
                    + h * h * (b2 * a0[m] + b5 * a1[m]))
        v_out[m] = ((d0 * y0[m] + d3 * y1[m]) / h + d1 * v0[m] + d4 * v1[m]
                    + h * (d2 * a0[m] + d5 * a1[m]))


@internal_kernel
def _newton(problem, step, y, v, w, eta, tol, stats):
    """Simplified Newton iteration for the stage increments ``w.Zy, w.Zv`` (started from them) of
    the step ``step = (t, h)``.

    Returns ``(converged, iterations, theta, eta)``: ``theta`` is the last contraction rate and
    ``eta = theta / (1 - theta)`` bounds the remaining error by ``eta ||dW||``; convergence means
    ``eta ||dW|| <= tol`` in the scaled norm. Fails on a non-finite correction, on divergence
    (``theta >= 0.99``) or when the error predicted after the remaining iterations exceeds ``tol``
    -- unless the corrections are already below ``NEWTON_NOISE`` (a few per cent of the error
    tolerance): then the iteration has reached the rounding-error floor of ``a(t, y, v)`` (stiff,
    strongly coupled systems at tight tolerances) and the iterate is accepted.
    """
    t, h = step
    n = y.shape[0]
    Zy, Zv, Wy, Wv, Fa, ry, rv = w.Zy, w.Zv, w.Wy, w.Wv, w.Fa, w.ry, w.rv
    dWy, dWv, cy, cv, cdy, cdv = w.dWy, w.dWv, w.cy, w.cv, w.cdy, w.cdv
    y_st, v_st, sc, Ca = w.y_st, w.v_st, w.sc, w.Ca
    mu_r = GAMMA / h
    mu_c = complex(ALPHA, -BETA) / h
    Ti = T_INV_RADAU
    T = T_RADAU
    for k in range(3):
        for m in range(n):
            Wy[k, m] = Ti[k, 0] * Zy[0, m] + Ti[k, 1] * Zy[1, m] + Ti[k, 2] * Zy[2, m]
            Wv[k, m] = Ti[k, 0] * Zv[0, m] + Ti[k, 1] * Zv[1, m] + Ti[k, 2] * Zv[2, m]
    eta = max(eta, UROUND) ** 0.8
    theta = 0.0
    norm_old = 1.0
    for it in range(NEWTON_MAX_ITER):
        for i in range(3):
            for m in range(n):
                y_st[m] = y[m] + Zy[i, m]
                v_st[m] = v[m] + Zv[i, m]
            problem_rhs(t + C[i] * h, y_st, v_st, Fa[i], problem)
        stats[RHS_CALLS] += 3
        # residual in transformed variables, T^-1 F - (Lambda W) / h, where the position part of
        # T^-1 F is T^-1 (v0 + Zv) = rowsum(T^-1) v0 + Wv
        for m in range(n):
            f0, f1, f2 = Fa[0, m], Fa[1, m], Fa[2, m]
            wy0, wy1, wy2 = Wy[0, m], Wy[1, m], Wy[2, m]
            wv0, wv1, wv2 = Wv[0, m], Wv[1, m], Wv[2, m]
            ry[0, m] = ROWSUM_T_INV[0] * v[m] + wv0 - GAMMA * wy0 / h
            rv[0, m] = Ti[0, 0] * f0 + Ti[0, 1] * f1 + Ti[0, 2] * f2 - GAMMA * wv0 / h
            cy[m] = complex(ROWSUM_T_INV[1] * v[m] + wv1 - (ALPHA * wy1 + BETA * wy2) / h,
                            ROWSUM_T_INV[2] * v[m] + wv2 - (ALPHA * wy2 - BETA * wy1) / h)
            cv[m] = complex(Ti[1, 0] * f0 + Ti[1, 1] * f1 + Ti[1, 2] * f2
                            - (ALPHA * wv1 + BETA * wv2) / h,
                            Ti[2, 0] * f0 + Ti[2, 1] * f1 + Ti[2, 2] * f2
                            - (ALPHA * wv2 - BETA * wv1) / h)
        _reduced_solve(w.lu_r, w.piv_r, mu_r, Ca, ry[0], rv[0], dWy[0], dWv[0])
        _reduced_solve(w.lu_c, w.piv_c, mu_c, Ca, cy, cv, cdy, cdv)
        for m in range(n):
            dWy[1, m] = cdy[m].real
            dWy[2, m] = cdy[m].imag
            dWv[1, m] = cdv[m].real
            dWv[2, m] = cdv[m].imag
        norm = _rms_stages(dWy, dWv, sc)
        if not np.isfinite(norm):
            return False, it + 1, theta, eta
        stalled = False
        if it > 0:
            theta = norm / norm_old
            stalled = (theta >= 0.99
                       or theta ** (NEWTON_MAX_ITER - 1 - it) / (1.0 - theta) * norm > tol)
            if stalled and norm > NEWTON_NOISE:
                return False, it + 1, theta, eta
            if not stalled:
                eta = theta / (1.0 - theta)
        for m in range(n):
            wy0 = Wy[0, m] + dWy[0, m]
            wy1 = Wy[1, m] + dWy[1, m]
            wy2 = Wy[2, m] + dWy[2, m]
            wv0 = Wv[0, m] + dWv[0, m]
            wv1 = Wv[1, m] + dWv[1, m]
            wv2 = Wv[2, m] + dWv[2, m]
            Wy[0, m], Wy[1, m], Wy[2, m] = wy0, wy1, wy2
            Wv[0, m], Wv[1, m], Wv[2, m] = wv0, wv1, wv2
            for i in range(3):
                Zy[i, m] = T[i, 0] * wy0 + T[i, 1] * wy1 + T[i, 2] * wy2
                Zv[i, m] = T[i, 0] * wv0 + T[i, 1] * wv1 + T[i, 2] * wv2
        if stalled:
            # the corrections stagnate at rounding-error level, far below the error tolerance:
            # accept, and do not report it as slow convergence (a new Jacobian would not help)
            return True, it + 1, 0.0, eta
        if eta * norm <= tol or norm == 0.0:
            return True, it + 1, theta, eta
        norm_old = norm
    return False, NEWTON_MAX_ITER, theta, eta


@internal_kernel
def _error_estimate(problem, t, h, y, v, w, refine, stats):
    """Scaled norm of the embedded error estimate, which is left in ``w.ey, w.ev``.

    With ``refine`` (first step, or after a rejection) and a norm above 1, the estimate is
    recomputed once with ``f`` at ``z0 + err`` instead of ``f(t0, z0)``, which removes spuriously
    large estimates of very stiff components.
    """
    n = y.shape[0]
    g = GAMMA / h
    Zy, Zv, ey, ev, y_st, v_st, a_st = w.Zy, w.Zv, w.ey, w.ev, w.y_st, w.v_st, w.a_st
    ry = w.ry[0]
    rv = w.rv[0]
    a = w.a
    for m in range(n):
        ry[m] = g * (E_ERR[0] * Zy[0, m] + E_ERR[1] * Zy[1, m] + E_ERR[2] * Zy[2, m])
        rv[m] = g * (E_ERR[0] * Zv[0, m] + E_ERR[1] * Zv[1, m] + E_ERR[2] * Zv[2, m])
        y_st[m] = v[m] + ry[m]
        v_st[m] = a[m] + rv[m]
    _reduced_solve(w.lu_r, w.piv_r, g, w.Ca, y_st, v_st, ey, ev)
    err = _rms(ey, ev, w.sc)
    if refine and err > 1.0:
        for m in range(n):
            y_st[m] = y[m] + ey[m]
            v_st[m] = v[m] + ev[m]
        problem_rhs(t, y_st, v_st, a_st, problem)
        stats[RHS_CALLS] += 1
        for m in range(n):
            y_st[m] = v_st[m] + ry[m]
            v_st[m] = a_st[m] + rv[m]
        _reduced_solve(w.lu_r, w.piv_r, g, w.Ca, y_st, v_st, ey, ev)
        err = _rms(ey, ev, w.sc)
    return err


@kernel
def newton_tolerance(rtol):
    """Newton stopping threshold in the scaled norm: ``max(10 eps / rtol, min(0.03, rtol^1/2))``."""
    return max(10.0 * UROUND / rtol, min(0.03, math.sqrt(rtol)))


@kernel
def single_step(problem, t, y, v, h, settings, result):
    """One step of size ``h`` from ``(t, y, v)`` with a fresh Jacobian and zero starting values,
    at the tolerances of ``settings`` (:class:`~hubbeam.core.inputs.IntegratorSettings`).

    Writes the solution and the error estimate into ``result = (y1, v1, err_y, err_v)``; returns
    ``(newton_converged, scaled_error_norm)``. A diagnostic for tests of the method's order and
    its error estimate, built from the same blocks as :func:`radau5`.
    """
    y1, v1, err_y, err_v = result
    rtol, atol = settings.rtol, settings.atol
    w = workspace(y.shape[0])
    stats = np.zeros(len(STAT_NAMES), np.int64)
    problem_rhs(t, y, v, w.a, problem)
    jacobian(problem, t, y, v, w, stats)
    _factorize(h, w, stats)
    _scale(y, v, y, v, rtol, atol, w.sc)
    ok = _newton(problem, (t, h), y, v, w, 1.0, newton_tolerance(rtol), stats)[0]
    for m in range(y.shape[0]):
        y1[m] = y[m] + w.Zy[2, m]
        v1[m] = v[m] + w.Zv[2, m]
    _scale(y, v, y1, v1, rtol, atol, w.sc)
    err = _error_estimate(problem, t, h, y, v, w, False, stats)
    _copy(w.ey, err_y)
    _copy(w.ev, err_v)
    return ok, err


# --------------------------------------------------------------------------- driver
@inline_kernel
def radau5(problem, start, t_stops, settings, watch, trajectory, stats):
    """Integrate ``y'' = a(t, y, y')`` from ``t_out[0]`` to ``t_out[-1]`` with Radau IIA (order 5).

    Parameters
    ----------
    problem : namedtuple of a class registered with :func:`register_rhs`.
    start : ``(y0, v0)``, (N,) positions and velocities at ``t_out[0]``.
    t_stops : sorted times that no step may cross (discontinuities of the forcing, such as the
        end of a maneuver, or a sampled controller's samples and input switches, where the
        problem's hooks run, :func:`register_hooks`); times outside ``(t_out[0], t_out[-1]]`` are
        ignored.
    settings : :class:`~hubbeam.core.inputs.IntegratorSettings`: ``rtol`` and ``atol`` of every
        component of ``(y, v)`` (every accepted step has an error estimate of weighted RMS
        norm <= 1, see the module docstring); ``tip_limit``: the run stops with status
        ``LEFT_RANGE`` after the first accepted step with ``|watch . y| > tip_limit``;
        ``max_steps``: budget of attempted steps (accepted, rejected and Newton failures);
        ``first_step``: first step size (``<= 0`` picks ``INITIAL_STEP_FRACTION (t_out[-1] -
        t_out[0])``); ``fixed_step``: if True every step has size ``first_step`` (shortened only
        to land on a stop or the end, or halved after a Newton failure), uses a fresh Jacobian and
        is accepted without error control (for convergence studies).
    watch : (N,) weights of the watched quantity (the tip deflection).
    trajectory : :class:`~hubbeam.core.inputs.Trajectory` ``(t_out, y_out, v_out)``: increasing
        output times (n_out,) and the caller-allocated dense output (n_out, N) written there;
        rows after the stop are NaN.
    stats : (6,) int64 caller-allocated counters, see ``STAT_NAMES``.

    Returns ``(status, t_stop)``: a code of ``STATUS_NAMES`` and the time reached. Outputs are
    written for every output time up to the last accepted step (for ``LEFT_RANGE``, up to and
    including the step that crossed the limit, ``t_stop``).
    """
    y0, v0 = start
    return _march(problem, (y0.copy(), v0.copy()), workspace(y0.shape[0]), t_stops, settings,
                  watch, trajectory, stats)


@internal_kernel
def _march(problem, state, w, t_stops, settings, watch, trajectory, stats):
    """:func:`radau5` from ``state = (y, v)`` (overwritten: the state as it goes) with the work
    arrays ``w`` of :func:`workspace`: the whole integration, allocating nothing."""
    y, v = state
    t_out, y_out, v_out = trajectory
    rtol, atol, watch_limit, max_steps, h_init, fixed_step = settings
    n = y.shape[0]
    n_out = t_out.shape[0]
    t = t_out[0]
    t_end = t_out[n_out - 1]
    span = t_end - t
    for k in range(stats.shape[0]):
        stats[k] = 0
    for k in range(n_out):
        for m in range(n):
            y_out[k, m] = np.nan
            v_out[k, m] = np.nan
    a, y1, v1, a1, sc = w.a, w.y1, w.v1, w.a1, w.sc
    Zy, Zv, Zy_acc, Zv_acc = w.Zy, w.Zv, w.Zy_acc, w.Zv_acc
    at_stop(t, y, v, problem)
    problem_rhs(t, y, v, a, problem)
    stats[RHS_CALLS] += 1
    if not (_all_finite(y) and _all_finite(v) and _all_finite(a)):
        return NON_FINITE, t
    _copy(y, y_out[0])
    _copy(v, v_out[0])
    i_out = 1
    i_stop = 0
    while i_stop < t_stops.shape[0] and t_stops[i_stop] <= t:
        i_stop += 1

    tol_newton = newton_tolerance(rtol)
    h = h_init if h_init > 0.0 else INITIAL_STEP_FRACTION * span
    h_acc = h            # size of the last accepted step
    err_acc = 1e-2       # error norm of the last accepted step (Gustafsson's controller)
    eta = 1.0
    rejected = False     # the previous attempt failed the error test
    need_jac = True      # evaluate J at the current point before the next attempt
    jac_current = False  # J was evaluated at the current point
    h_lu = 0.0           # step size of the current LU factors (0: none)
    fresh = True         # no step accepted since the start or a restart (register_hooks)
    attempts = 0
    while t < t_end:
        # land exactly on the next stop or the end, without leaving a sliver of a step
        t_next = t_end
        if i_stop < t_stops.shape[0] and t_stops[i_stop] < t_end:
            t_next = t_stops[i_stop]
        remaining = t_next - t
        if remaining <= 1.05 * h:
            h = remaining
        elif remaining < 2.0 * h:
            h = 0.5 * remaining
        if h < 10.0 * UROUND * max(abs(t), span):
            return STEP_UNDERFLOW, t
        if attempts >= max_steps:
            return TOO_MANY_STEPS, t
        attempts += 1
        if need_jac:
            jacobian(problem, t, y, v, w, stats)
            jac_current = True
            need_jac = False
            h_lu = 0.0
        # after a restart the interval to the next stop is the previous one's length to rounding:
        # the factors of that length serve (simplified Newton), not refactored for an ulp
        if h != h_lu and not (fresh and abs(h - h_lu) <= SAME_STEP * h):
            _factorize(h, w, stats)
            h_lu = h
        if fresh:
            for i in range(3):
                for m in range(n):
                    Zy[i, m] = 0.0
                    Zv[i, m] = 0.0
        else:
            _extrapolate_stages(h / h_acc, w)
        _scale(y, v, y, v, rtol, atol, sc)
        converged, nit, theta, eta = _newton(problem, (t, h), y, v, w, eta, tol_newton, stats)
        if not converged:
            # retry with a fresh Jacobian, or with half the step if J is fresh already
            stats[NEWTON_FAILURES] += 1
            if jac_current:
                h *= 0.5
            else:
                need_jac = True
            eta = 1.0
            continue
        for m in range(n):
            y1[m] = y[m] + Zy[2, m]
            v1[m] = v[m] + Zv[2, m]
        err = 0.0
        if not fixed_step:
            _scale(y, v, y1, v1, rtol, atol, sc)
            err = _error_estimate(problem, t, h, y, v, w, fresh or rejected, stats)
        fac = SAFETY * (2 * NEWTON_MAX_ITER + 1) / (2 * NEWTON_MAX_ITER + nit)
        if not (err <= 1.0):
            stats[REJECTED] += 1
            factor = fac * err ** -0.25 if np.isfinite(err) else MIN_FACTOR
            h *= max(MIN_FACTOR, min(1.0, factor))
            rejected = True
            need_jac = False  # keep J: a rejection is about h, not about a stale Jacobian
            continue
        # ---- accepted
        t1 = t + h
        problem_rhs(t1, y1, v1, a1, problem)
        stats[RHS_CALLS] += 1
        stats[ACCEPTED] += 1
        if not (_all_finite(y1) and _all_finite(v1) and _all_finite(a1)):
            return NON_FINITE, t1
        after_step(t, h, (y, v, a), (y1, v1, a1), problem)
        while i_out < n_out and t_out[i_out] <= t1 * (1.0 + 4.0 * UROUND):
            s = min(1.0, (t_out[i_out] - t) / h)
            hermite_interpolate(s, h, (y, v, a), (y1, v1, a1), y_out[i_out], v_out[i_out])
            i_out += 1
        if fixed_step:
            h_new = h_init
        else:
            e = max(err, 1e-10)
            factor = fac * e ** -0.25
            if not fresh:
                factor = min(factor, factor * (h / h_acc) * (err_acc / e) ** 0.25)
            factor = max(MIN_FACTOR, min(MAX_FACTOR, factor))
            if KEEP_STEP_LOW <= factor <= KEEP_STEP_HIGH:
                factor = 1.0
            if rejected:
                factor = min(factor, 1.0)
            h_new = h * factor
            err_acc = max(err, 1e-2)
        h_acc = h
        for i in range(3):
            for m in range(n):
                Zy_acc[i, m] = Zy[i, m]
                Zv_acc[i, m] = Zv[i, m]
        t = t1
        landed = False
        while i_stop < t_stops.shape[0] and t_stops[i_stop] <= t:
            i_stop += 1
            landed = True
        watched = 0.0
        for m in range(n):
            y[m] = y1[m]
            v[m] = v1[m]
            a[m] = a1[m]
            watched += watch[m] * y[m]
        if abs(watched) > watch_limit:
            return LEFT_RANGE, t
        rejected = False
        jac_current = False
        need_jac = fixed_step or theta > JACOBIAN_REFRESH
        h = h_new
        fresh = False
        if landed and at_stop(t, y, v, problem):
            # the forcing jumped: restart from (t, y, v) with the new accelerations
            problem_rhs(t, y, v, a, problem)
            stats[RHS_CALLS] += 1
            if not _all_finite(a):
                return NON_FINITE, t
            fresh = True
    return SUCCESS, t
