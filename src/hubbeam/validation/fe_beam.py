"""Finite-element model of the rotating beam: an independent check of the Ritz (assumed-mode) model.

Euler-Bernoulli beam of cubic Hermite elements (nodal deflection and slope), clamped at the hub
radius ``rA`` of a hub spinning at constant ``Omega``, with a tip body attached at ``0 <= l <= L``:
its mass ``m_t`` at its centre ``e`` beyond the attachment along the beam's tangent there, which
moves by ``w_c = w(l) + e w'(l)``, and its rotary inertia ``J_t`` about that centre, which turns
with the slope ``w'(l)`` (``docs/tip-body.md``; ``e = J_t = 0``: a point mass). The deflection
``w`` is either in the plane of rotation (in-plane, lag) or perpendicular to it (flapwise). The
free vibrations obey ``(M + R) a'' + K(Omega) a = 0`` with

    M = int rhoA N^T N dx + m_t N_c^T N_c,          N_c = N(l) + e N'(l),    R = J_t N'(l)^T N'(l)
    K(Omega) = int EI N''^T N'' dx + int T N'^T N' dx + m_t (rA + l + e) e N'(l)^T N'(l)
               - c Omega^2 M,   c = 1 in-plane, 0 flapwise,
    T(x) = Omega^2 [ int_x^L rhoA(s) (rA + s) ds + m_t (rA + l + e) H(l - x) ],

``T`` the centrifugal tension of the undeformed beam and the body, the body's own term the
centrifugal pull on its centre as the slope tilts it (its centre comes in by ``e w'(l)^2 / 2``),
``-Omega^2 M`` the softening of in-plane motion (the centrifugal force of a point moved sideways
has a component along the motion; a rotation of the body has none). These are the continuum
equations behind Eq. (31) with the tip-mass terms of the Appendix: ``q^T D q = int T w'^2 dx /
Omega^2`` plus the body's term, so the Ritz frequencies of ``(K2 + Omega^2 D - c Omega^2 M2, M2 +
J_t f2'(l)^T f2'(l))`` (``hubbeam.model.eigen``, ``hubbeam.validation.rotating_eigen``) converge to
these as modes are added, and these converge under mesh refinement at the rate of cubic elements.
The rotary inertia is ``J_t`` about the axis normal to the plane of rotation: only in-plane
motion turns the body about it (flapwise, the body's inertia about other axes would enter).

The mesh has a node at every station of the property tables (where the properties have kinks), at
the tip-mass position and on a uniform grid of ``n_elements`` elements; element integrals use a
5-point Gauss rule, exact for the piecewise-linear ``rhoA``, ``EI`` and the cubic tension on each
element. The model shares only the beam description (``rhoA_at``, ``EI_at``, ``outboard_moment``)
and the check of the tip body with the Ritz model: other shape functions, quadrature and assembly.
"""

from __future__ import annotations

import itertools
from typing import NamedTuple

import numpy as np
import scipy.linalg

from hubbeam.model.parameters import TipMass, check_tip

DIRECTIONS = ("flapwise", "inplane")
#: coefficient of the -Omega^2 M softening per direction
_SOFTENING = {"flapwise": 0.0, "inplane": 1.0}
_GAUSS_T, _GAUSS_W = np.polynomial.legendre.leggauss(5)


def mesh(params, n_elements: int, tip_position: float | None = None) -> np.ndarray:
    """Node abscissae (m): a uniform grid of ``n_elements`` elements, every station and the tip."""
    if not isinstance(n_elements, (int, np.integer)) or n_elements < 1:
        raise ValueError(f"n_elements = {n_elements!r}: expected an integer >= 1")
    nodes = np.concatenate([np.linspace(0.0, params.L, n_elements + 1),
                            np.asarray(params.stations, dtype=float),
                            [] if tip_position is None else [float(tip_position)]])
    nodes = np.unique(nodes)
    # merge nodes closer than a rounding error (a station on the grid computed twice)
    return nodes[np.append(True, np.diff(nodes) > 1e-12 * params.L)]


def _hermite(xi, h):
    """Cubic Hermite shape functions on an element of length ``h`` and their x-derivatives.

    ``xi`` in [0, 1]; returns N, N', N'' of shape ``xi.shape + (4,)`` for the element DOFs
    (w_a, w'_a, w_b, w'_b).
    """
    xi = np.asarray(xi, dtype=float)[..., None]
    N = np.concatenate([1 - 3 * xi**2 + 2 * xi**3, h * (xi - 2 * xi**2 + xi**3),
                        3 * xi**2 - 2 * xi**3, h * (xi**3 - xi**2)], axis=-1)
    dN = np.concatenate([(-6 * xi + 6 * xi**2) / h, 1 - 4 * xi + 3 * xi**2,
                         (6 * xi - 6 * xi**2) / h, 3 * xi**2 - 2 * xi], axis=-1)
    ddN = np.concatenate([(-6 + 12 * xi) / h**2, (-4 + 6 * xi) / h,
                          (6 - 12 * xi) / h**2, (6 * xi - 2) / h], axis=-1)
    return N, dN, ddN


class FeMatrices(NamedTuple):
    """Global matrices of the clamped beam, root DOFs removed: translational mass ``M`` (beam and
    tip body), bending stiffness ``K``, geometric stiffness per ``Omega^2`` ``G`` (tension and the
    body's offset term) and the body's rotary inertia ``R`` (module docstring)."""

    M: np.ndarray
    K: np.ndarray
    G: np.ndarray
    R: np.ndarray


def matrices(params, tip=None, n_elements: int = 160, root_spring=None) -> FeMatrices:
    """The :class:`FeMatrices` of the beam ``params`` with the tip body ``tip`` (a
    :class:`~hubbeam.model.parameters.TipMass` or ``None``, checked by ``check_tip``), clamped at the
    root, or, with a ``root_spring`` (``hubbeam.model.root.RootSpring``), hinged there: the root's
    deflection held, its slope restrained by the spring's stiffness and carrying the clamp's
    inertia (the hub held)."""
    tip = TipMass(0.0, params.L) if tip is None else tip
    check_tip(tip, params.L)
    mass, position, offset = tip.mass, tip.position, tip.offset
    nodes = mesh(params, n_elements, position)
    n_dof = 2 * nodes.size
    M, Kb, G, R = (np.zeros((n_dof, n_dof)) for _ in range(4))
    xi = 0.5 * (_GAUSS_T + 1.0)
    lever = params.rA + position + offset  # of the body's centre
    for e, (a, b) in enumerate(itertools.pairwise(nodes)):
        h = b - a
        x = a + h * xi
        weights = 0.5 * h * _GAUSS_W
        N, dN, ddN = _hermite(xi, h)
        tension = params.outboard_moment(x) + mass * lever * (x < position)
        dofs = slice(2 * e, 2 * e + 4)
        M[dofs, dofs] += (N.T * weights * params.rhoA_at(x)) @ N
        Kb[dofs, dofs] += (ddN.T * weights * params.EI_at(x)) @ ddN
        G[dofs, dofs] += (dN.T * weights * tension) @ dN
    tip_node = int(np.argmin(np.abs(nodes - position)))
    body = slice(2 * tip_node, 2 * tip_node + 2)  # (w(l), w'(l))
    centre = np.array([1.0, offset])  # w_c = w(l) + e w'(l)
    M[body, body] += mass * np.outer(centre, centre)
    G[2 * tip_node + 1, 2 * tip_node + 1] += mass * lever * offset
    R[2 * tip_node + 1, 2 * tip_node + 1] += tip.inertia
    free = slice(2, None)  # clamped root: w(0) = w'(0) = 0
    if root_spring is not None:  # hinged root: w(0) = 0, w'(0) on the spring
        Kb[1, 1] += root_spring.stiffness
        R[1, 1] += root_spring.clamp_inertia
        free = slice(1, None)
    return FeMatrices(*(A[free, free] for A in (M, Kb, G, R)))


def frequencies(params, speeds, direction: str, tip=None, n_elements: int = 160,
                n_frequencies: int = 6, root_spring=None) -> np.ndarray:
    """Lowest ``n_frequencies`` circular frequencies (rad s-1) at each hub speed of ``speeds``.

    ``direction`` is ``"flapwise"`` (stiffening only) or ``"inplane"`` (stiffening and the
    ``-Omega^2`` softening). Returns shape ``(len(speeds), n_frequencies)``, ascending.

    Solved as ``M a = mu K a``, ``omega = mu^-1/2`` for the largest ``mu``: the lowest modes of
    ``K a = omega^2 M a`` lose digits in proportion to the condition number of ``K`` (about
    ``n_elements^4``, 1e-8 relative at 80 elements), the largest ``mu`` do not (1e-9 at 160).
    ``K`` is positive definite in both directions: in-plane, ``int T w'^2 >= Omega^2 int rhoA
    w^2`` for every ``w`` with ``w(0) = 0`` when ``rA > 0`` (``hubbeam.model.eigen``: no critical
    speed), for a point mass; a body's offset adds to both sides. ``tip`` as in :func:`matrices`;
    its rotary inertia is defined in-plane only; ``root_spring`` as in :func:`matrices`.
    """
    if direction not in _SOFTENING:
        raise ValueError(f"direction = {direction!r}: expected one of {', '.join(DIRECTIONS)}")
    if direction == "flapwise" and tip is not None and tip.inertia != 0.0:
        raise ValueError(f"tip_mass.inertia = {tip.inertia!r} with direction = 'flapwise': expected 0 "
                         "(the rotary inertia about the hub axis turns with in-plane motion only)")
    fe = matrices(params, tip, n_elements, root_spring)
    mass = fe.M + fe.R
    if not 1 <= n_frequencies <= mass.shape[0]:
        raise ValueError(f"n_frequencies = {n_frequencies!r}: expected 1..{mass.shape[0]} "
                         f"(the free DOFs of {n_elements} elements)")
    out = []
    for speed in np.atleast_1d(np.asarray(speeds, dtype=float)):
        K = fe.K + speed**2 * (fe.G - _SOFTENING[direction] * fe.M)
        mu = scipy.linalg.eigh(mass, K, eigvals_only=True,
                               subset_by_index=[mass.shape[0] - n_frequencies, mass.shape[0] - 1])
        out.append(mu[::-1] ** -0.5)
    return np.array(out)


def ritz_frequencies(params, speeds, shapes, tip=None, n_elements: int = 80, count: int = 3) -> np.ndarray:
    """The lowest ``count`` in-plane circular frequencies (rad s-1) at each hub speed of ``speeds``
    of the Ritz model in the trial functions ``shapes`` built from the elements' matrices: each
    function enters as its nodal values and slopes (``shapes(x, derivative)``, shape ``(len(x),
    k)``; its cubic Hermite interpolant, exact for cubics), so that the mass and stiffness are
    ``Phi^T (M + R) Phi`` and ``Phi^T K(Omega) Phi`` (a basis to compare with hubbeam's, assembled
    apart from it)."""
    tip = TipMass(0.0, params.L) if tip is None else tip
    nodes = mesh(params, n_elements, tip.position)[1:]  # the root's DOFs are removed
    values, slopes = shapes(nodes, 0), shapes(nodes, 1)
    Phi = np.empty((2 * nodes.size, values.shape[1]))
    Phi[0::2], Phi[1::2] = values, slopes
    fe = matrices(params, tip, n_elements)
    mass = Phi.T @ (fe.M + fe.R) @ Phi
    out = []
    for speed in np.atleast_1d(np.asarray(speeds, dtype=float)):
        stiffness = Phi.T @ (fe.K + speed**2 * (fe.G - fe.M)) @ Phi
        out.append(np.sqrt(scipy.linalg.eigh(stiffness, mass, eigvals_only=True)[:count]))
    return np.array(out)
