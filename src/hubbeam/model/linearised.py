"""The beam's vibrations at constant hub speed: Eqs. (29)-(31) and their eigenproblems, in one place.

Hold the hub speed at ``theta_dot = Omega`` (``theta_ddot = 0``). The q-rows of the equations of
motion (Eq. 24 with Eqs. 29-33) then have constant coefficients; about the steady centrifugal
stretch ``q1s = Omega^2 (K1 - Omega^2 M1)^-1 V1^T``, ``q2s = 0`` the deviation ``x = (q1 - q1s,
q2)`` obeys exactly

    M x'' + G x' + K x = 0,     M = diag(M1, M2t),    G = 2 Omega [[0, -R], [R^T, 0]],   (29)
                                K = diag(K1 - Omega^2 M1, K22(Omega)),                    (30)

with the transverse stiffness of Eq. (31), ``K22 = K2 - Omega^2 B`` and

    TLAM:      B = M2                 (the underlined D terms removed)
    FOAM:      B = M2 - D             (centrifugal softening and stiffening)
    flapwise:  B = -D                 (out of the plane of rotation: no softening, no coupling)

``M2``, ``D``, ``R`` include the tip-mass terms of Section 4.4 when the matrices do; ``M2t = M2 +
Jt f2'(l)^T f2'(l)`` adds a tip body's rotary inertia (``core.system_matrices.transverse_mass``),
which has no centrifugal term of its own, so ``B`` keeps ``M2`` (``docs/tip-body.md``). The
transverse block alone is ``M2t q2'' + K22 q2 = 0`` (``G = 0``). A model's variant is its
``linearisation`` in the table of models (``hubbeam.model.models``); the variants' terms follow from
the models' traits (``softening_terms``: the ``D`` terms; ``keeps_axial``: the axial block). The flapwise variant is the
transverse motion perpendicular to the plane of rotation (``w = f2 q3``), which the published
rotating-cantilever tables tabulate (:mod:`hubbeam.validation.rotating_eigen` derives it).

Eigenproblems, both reduced by the Cholesky factor of the mass matrix and solved for stacks of
speeds at once: the symmetric one ``K22 v = omega^2 M2t v`` and the gyroscopic quadratic one
``(lambda^2 M + lambda G + K) x = 0`` (:func:`quadratic_eigenvalues`).
"""

import numpy as np

from hubbeam.core.system_matrices import rotary_mass, transverse_mass
from hubbeam.model.models import MODELS

#: ``B`` of ``K22 = K2 - Omega^2 B`` as ``a M2 - c D``: variant -> ``(a, c)`` (Eq. 31): the
#: linearisation of each model (``c = 1`` where it keeps the softening terms) and the flapwise one
CENTRIFUGAL_TERMS = {**{m.linearisation: (1.0, 1.0 if m.softening_terms else 0.0)
                        for m in MODELS.values()},
                     "flapwise": (0.0, 1.0)}
#: the variants with the axial coordinates and their Coriolis coupling (Eqs. 29, 30)
AXIAL_MODELS = tuple(dict.fromkeys(m.linearisation for m in MODELS.values() if m.keeps_axial))


def _terms(model):
    try:
        return CENTRIFUGAL_TERMS[model]
    except KeyError:
        raise ValueError(f"model = {model!r}: the constant-speed equations are defined for "
                         f"{', '.join(CENTRIFUGAL_TERMS)}") from None


def centrifugal_matrix(M2, D, model):
    """``B`` of ``K22(Omega) = K2 - Omega^2 B`` (Eq. 31): ``M2`` (TLAM), ``M2 - D`` (FOAM),
    ``-D`` (flapwise). ``M2`` and ``D`` may be stacks with the same leading axes."""
    a, c = _terms(model)
    return a * M2 - c * D


def transverse_stiffness(K2, M2, D, model, speed):
    """``K22(Omega) = K2 - Omega^2 B`` of Eq. (31) (``B``: :func:`centrifugal_matrix`).

    ``speed`` (rad s-1) of shape ``s`` gives shape ``s + (n, n)``; stacked ``M2``, ``D`` of shape
    ``p + (n, n)`` broadcast against ``s`` (give them singleton axes to form an outer product).
    """
    omega2 = np.square(np.asarray(speed, dtype=float))[..., None, None]
    return K2 - omega2 * centrifugal_matrix(M2, D, model)


def axial_stretch(sm, speed):
    """The steady centrifugal stretch ``q1s = Omega^2 (K1 - Omega^2 M1)^-1 V1`` at the hub speed
    ``Omega = speed`` (the q1 rows of Eq. 24 with ``q2 = 0`` and every rate but the hub's zero;
    Eqs. 29-30)."""
    omega2 = float(speed) ** 2
    return omega2 * np.linalg.solve(sm.K1 - omega2 * sm.M1, sm.V1)


def constant_speed_matrices(sm, model, speed, axial=False):
    """``(M, G, K)`` of the free vibrations at hub speed ``speed`` (Eqs. 29-31).

    ``sm`` is a :class:`~hubbeam.model.matrices.SystemMatrices`; ``model`` a key of
    :data:`CENTRIFUGAL_TERMS`. Without ``axial`` the transverse block ``(M2, 0, K22)``; with it
    the coupled axial-transverse system of ``x = (q1, q2)`` (TLAM, FOAM only). ``speed`` of shape
    ``s`` gives ``G`` and ``K`` of shape ``s + (N, N)``; ``M`` does not depend on the speed. The
    transverse mass block is ``M2t`` (with a tip body's rotary inertia), the centrifugal one ``M2``.
    """
    k22 = transverse_stiffness(sm.K2, sm.M2, sm.D, model, speed)
    mass = transverse_mass(sm)
    if not axial:
        return mass, np.zeros_like(k22), k22
    if model not in AXIAL_MODELS:
        raise ValueError(f"model = {model!r}: the axial coupling is defined for "
                         f"{', '.join(AXIAL_MODELS)}")
    w = np.asarray(speed, dtype=float)[..., None, None]
    zero = np.zeros(k22.shape)
    M = np.block([[sm.M1, np.zeros_like(sm.M1)], [np.zeros_like(sm.M2), mass]])
    G = 2.0 * w * np.block([[zero, -np.broadcast_to(sm.R, zero.shape)],
                            [np.broadcast_to(sm.R.T, zero.shape), zero]])  # Eq. (29)
    K = np.block([[sm.K1 - w**2 * sm.M1, zero], [zero, k22]])  # Eqs. (30), (31)
    return M, G, K


def _reduced(A, B):
    """``C^-1 A C^-T`` with ``B = C C^T`` (Cholesky), for stacks; ``B`` symmetric positive definite."""
    Cinv = np.linalg.inv(np.linalg.cholesky(B))
    return Cinv @ A @ np.swapaxes(Cinv, -1, -2)


def symmetric_eigenvalues(A, B):
    """Ascending eigenvalues of ``A v = lambda B v`` for stacks of symmetric ``A``, SPD ``B``."""
    reduced = _reduced(A, B)
    return np.linalg.eigvalsh(0.5 * (reduced + np.swapaxes(reduced, -1, -2)))


def quadratic_eigenvalues(M, G, K):
    """Eigenvalues ``lambda`` of ``(lambda^2 M + lambda G + K) x = 0``, ``2N`` complex values.

    With ``M = C C^T`` (Cholesky) and ``y = C^T x`` the problem becomes ``lambda^2 y + lambda Gr y
    + Kr y = 0``, ``Gr = C^-1 G C^-T``, ``Kr = C^-1 K C^-T``, whose companion matrix ``[[0, I],
    [-Kr, -Gr]]`` has the eigenvalues ``lambda`` (LAPACK ``geev``, which balances the matrix).
    ``G`` and ``K`` may be stacks of shape ``s + (N, N)`` (one ``M``); the result has shape
    ``s + (2N,)``. Against Newton-refined eigenvalues of the beam (the first chordwise frequency
    of the published tables, slow modes near TLAM's critical speed) this is accurate to about
    1e-14 relative; the QZ algorithm on the unbalanced pencil ``([[0, I], [-K, -G]], [[I, 0],
    [0, M]])`` was off by up to 4e-10 and 1e-9 there, the stiff axial coordinates making ``|K|``
    1e7 to 1e8 times ``|M|``.
    """
    n = M.shape[-1]
    G, K = np.broadcast_arrays(G, K)
    stack = K.shape[:-2]
    companion = np.zeros(stack + (2 * n, 2 * n))
    companion[..., :n, n:] = np.eye(n)
    companion[..., n:, :n] = -_reduced(K, np.broadcast_to(M, K.shape))
    companion[..., n:, n:] = -_reduced(G, np.broadcast_to(M, G.shape))
    return np.linalg.eigvals(companion)


def frequencies_from_squares(omega_squared):
    """Circular frequencies from ``omega^2``; NaN where ``omega^2 < 0`` (beyond a critical speed)."""
    with np.errstate(invalid="ignore"):
        return np.where(omega_squared >= 0.0, np.sqrt(np.abs(omega_squared)), np.nan)


def pair_frequencies(eigenvalues):
    """One circular frequency ``|Im lambda|`` per conjugate pair, ascending, shape ``s + (N,)``
    from ``s + (2N,)`` eigenvalues; a divergent direction (real pair) shows as 0."""
    return np.sort(np.abs(np.imag(eigenvalues)), axis=-1)[..., ::2]


def eigenvalues(sm, model, speed, axial=False):
    """``omega^2`` (ascending, s^-2) of the transverse block, or with ``axial`` the complex
    ``lambda`` (s^-1) of the coupled gyroscopic system, at the speeds ``speed`` (shape ``s``)."""
    M, G, K = constant_speed_matrices(sm, model, speed, axial)
    if axial:
        return quadratic_eigenvalues(M, G, K)
    return symmetric_eigenvalues(K, np.broadcast_to(M, K.shape))


def frequencies(sm, model, speed, axial=False):
    """Circular frequencies (rad s-1, ascending) at the speeds ``speed``, shape ``s + (n,)`` or,
    with ``axial``, ``s + (2n,)``: NaN where ``K22`` is negative in a direction (transverse
    block), 0 for a divergent pair (coupled system)."""
    values = eigenvalues(sm, model, speed, axial)
    return pair_frequencies(values) if axial else frequencies_from_squares(values)


def stretch_foreshortening(sm, q1s: np.ndarray) -> np.ndarray:
    """``E(q1s) = sum_k w_k (f1(x_k) q1s) S(x_k)`` over the point cloud: the foreshortening of the
    exact kinetic energy (Eqs. 8-9) weighted by the stretch; CFOAM's ``K22`` gains ``Omega^2 E``."""
    return np.einsum("k,k,kij->ij", sm.w, sm.F1 @ q1s, sm.S)


def spin_matrices(sm, traits, speed: float, damping: np.ndarray, q1s: np.ndarray):
    """``(M, G, C, K)`` of a model's equations linearised about the steady spin at ``speed`` with
    the axial coordinates at ``q1s``: ``M z'' + (G + C) z' + K z = e_theta tau`` in the deviations
    ``z = (theta, [q1 - q1s], q2)`` (``hubbeam.linear.statespace``, whose module docstring and
    ``docs/linear-models.md`` derive them; ``traits`` a ``hubbeam.model.models.Model``,
    ``damping`` the ``(2, n, n)`` matrices ``[C1, C2]``)."""
    n = sm.M2.shape[0]
    Me, Ge, Ke = constant_speed_matrices(sm, traits.linearisation, speed, axial=traits.keeps_axial)
    Ke = np.array(Ke)
    if traits.exact_kinetic_energy:  # Eqs. 8-9
        Ke[-n:, -n:] += speed**2 * stretch_foreshortening(sm, q1s)
    Ce = np.zeros_like(Me)
    if traits.keeps_axial:
        Ce[:n, :n] = damping[0]
    Ce[-n:, -n:] = damping[1]
    N = 1 + Me.shape[0]
    M, G, C, K = (np.zeros((N, N)) for _ in range(4))
    M[1:, 1:], G[1:, 1:], C[1:, 1:], K[1:, 1:] = Me, Ge, Ce, Ke
    hub, coupling, _ = rotary_mass(sm)  # the q2 block has it already (constant_speed_matrices)
    M[0, 0] = sm.Jh + sm.Jb + 2.0 * sm.V1 @ q1s + q1s @ sm.M1 @ q1s + hub
    M[0, -n:] = M[-n:, 0] = sm.V2 + sm.R.T @ q1s + coupling
    if traits.keeps_axial:
        p = sm.V1 + sm.M1 @ q1s
        G[1:1 + n, 0] = -2.0 * speed * p
        if traits.hub_velocity_force:
            G[0, 1:1 + n] = 2.0 * speed * p
    return M, G, C, K
