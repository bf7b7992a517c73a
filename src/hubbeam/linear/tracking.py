"""Modes of a linear model and their tracking over a speed grid (damped Campbell diagrams).

A first-order model ``x' = A x`` of a mechanical system keeps the positions first and their rates
after them, ``x = (y, y')`` (``hubbeam.linear.statespace``: ``theta, q1, q2`` and their rates;
the hub angle only where the hub is free, ``q1`` only where the model keeps it). Each eigenpair
``A v = lambda v`` then has ``v = (u, lambda u)``; ``u`` is the mode shape.

Modes (:func:`state_modes`). The ``N`` eigenvalues of ``A`` (``N = 2 m``, LAPACK ``geev`` through
``numpy.linalg.eig``) give ``m`` modes, one per pair:

* a complex conjugate pair ``sigma +- i omega_d`` is one vibration mode, represented by its member
  with ``Im > 0``: frequency ``omega_d = |Im lambda|``, damping ratio ``zeta = -Re lambda / |lambda|``;
* the real eigenvalues (``geev`` returns them with an imaginary part of exactly 0) are paired by the
  shapes of their eigenvectors (largest MAC, below), as the pair ``+-sqrt(-k/m)`` of a direction of
  negative stiffness (TLAM beyond its critical speed) or the two real roots of an overdamped mode;
  the pair is one ``divergent`` mode of frequency 0, represented by its larger eigenvalue (for
  ``+-sigma`` the growing one, damping ratio -1);
* a ``rigid`` mode has ``|lambda|`` below the zero tolerance: the rigid-body rotation of a free hub
  (the hub angle is cyclic: a double, defective eigenvalue 0, which rounding splits by about
  ``sqrt(eps |A|)``, :data:`ZERO_TOLERANCE`). Its damping ratio is NaN; it is neither growing nor
  decaying. A prescribed hub has such a mode too: its angle and speed are states, the integrals of
  the input.

A mode is ``stable`` when ``Re lambda`` does not exceed the zero tolerance (undamped vibration modes
have ``Re lambda`` at rounding level).

Mode shapes are compared by the modal assurance criterion of complex vectors,
``MAC(u, v) = |u^H v|^2 / (|u|^2 |v|^2)`` (:func:`mac`), on the shapes scaled by coordinate
``weights`` (e.g. the square roots of the diagonal of the mass matrix, so that a hub angle in rad
and modal coordinates in kg^1/2 m weigh by their kinetic energies).

Tracking (:func:`track`): at the first speed the modes are ordered by frequency; from one speed to
the next, the modes are assigned to the previous speed's by the largest total MAC, an optimal
assignment (``scipy.optimize.linear_sum_assignment`` on ``1 - MAC``). A mode thus keeps its shape
identity where two frequency curves cross (uncoupled shapes) and where a weak coupling makes them
veer over a speed range narrower than the grid step, where sorting by frequency would swap them;
inside a veering range resolved by the grid, the shapes rotate into each other continuously and
the tracked curves follow the continuous branches.

Labels (:func:`dominant_content`): a rigid-body mode is ``hub``; every other mode is flexible,
``axial k`` when the axial coordinates hold the larger share of ``|w_i u_i|^2``, else ``bending k``
(the transverse share counts the hub's and the root's angles), ``k`` the coordinate with the
largest share inside the group.
:func:`numbered_by_frequency` then numbers each group's modes by their rank in frequency, the name
that stays distinct on a light free hub (where every bending mode's content is mostly the first
clamped-free function).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

#: ``|lambda|`` and ``Re lambda`` below ``ZERO_TOLERANCE * sqrt(max |A_ij|)`` count as zero. The
#: largest entries of ``A`` are stiffnesses over masses (s^-2), so the bound is a rate (s^-1). A
#: defective double eigenvalue 0 (the free hub's rigid rotation) may be split by rounding by up to
#: about ``sqrt(eps max |A_ij|)`` (``eps = 2.2e-16``); this is 10 times that, 1.3e-3 s^-1 for the
#: paper's beam with 5 + 5 modes (``max |A_ij| = 7.8e7 s^-2``), 2.8e-3 s^-1 with 10 + 10. The
#: hub's zero column makes LAPACK return that pair at 1e-13 s^-1, and the real parts of undamped
#: modes stay below 2e-12 s^-1.
ZERO_TOLERANCE = 10.0 * np.sqrt(np.finfo(float).eps)

#: coordinate group of a position state name, by its prefix
GROUPS = {"theta": "hub", "phi": "hub", "q1": "axial", "q2": "bending"}


@dataclass(frozen=True)
class Modes:
    """Modes of a stack of state matrices: leading axes ``s`` (speeds), ``m`` modes.

    ``eigenvalue`` (s, m) complex, the representative of each pair; ``shape`` (s, m, p) complex
    position parts of unit weighted norm, the largest weighted component real and positive;
    ``divergent``, ``rigid``, ``stable`` (s, m) bool; ``weights`` (p,).
    """

    eigenvalue: np.ndarray
    shape: np.ndarray
    divergent: np.ndarray
    rigid: np.ndarray
    stable: np.ndarray
    weights: np.ndarray

    @property
    def frequency(self) -> np.ndarray:
        """Damped circular frequency ``|Im lambda|`` (rad s-1); 0 for divergent and rigid modes."""
        return np.where(self.rigid, 0.0, np.abs(self.eigenvalue.imag))

    @property
    def damping_ratio(self) -> np.ndarray:
        """``-Re lambda / |lambda|``; NaN for a rigid mode."""
        with np.errstate(invalid="ignore", divide="ignore"):
            zeta = -self.eigenvalue.real / np.abs(self.eigenvalue)
        return np.where(self.rigid, np.nan, zeta)

    def take(self, order: np.ndarray) -> Modes:
        """The modes reordered along the mode axis by ``order`` (s, m) (e.g. :func:`track`)."""
        def pick(values):
            index = order.reshape(order.shape + (1,) * (values.ndim - order.ndim))
            return np.take_along_axis(values, index, axis=1)
        return Modes(pick(self.eigenvalue), pick(self.shape), pick(self.divergent),
                     pick(self.rigid), pick(self.stable), self.weights)


def mac(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Modal assurance criterion ``|u_i^H v_j|^2 / (|u_i|^2 |v_j|^2)`` of stacks of shapes.

    ``u`` (..., a, p) and ``v`` (..., b, p) complex or real; the result (..., a, b) lies in [0, 1].
    """
    inner = np.abs(np.einsum("...ip,...jp->...ij", np.conj(u), v)) ** 2
    norms = np.einsum("...ip,...ip->...i", np.conj(u), u).real[..., :, None] \
        * np.einsum("...jp,...jp->...j", np.conj(v), v).real[..., None, :]
    return inner / norms


def _zero_tolerance(A: np.ndarray) -> np.ndarray:
    """Per matrix of the stack: the magnitude (s^-1) below which an eigenvalue counts as zero."""
    return ZERO_TOLERANCE * np.sqrt(np.max(np.abs(A), axis=(-2, -1)))


def _normalised(u: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Shapes (..., p) scaled to unit weighted norm, the largest weighted component real > 0."""
    scaled = u * weights
    largest = np.take_along_axis(scaled, np.argmax(np.abs(scaled), axis=-1)[..., None], axis=-1)
    phase = largest / np.abs(largest)
    return u / (phase * np.linalg.norm(scaled, axis=-1, keepdims=True))


def _representatives(values: np.ndarray, shapes: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Indices of one eigenvalue per pair at one speed: ``Im > 0`` of each complex pair, the larger
    of each real pair (real eigenvalues paired greedily, largest first, by the MAC of their
    shapes). Ordered by frequency, then real part."""
    chosen = list(np.flatnonzero(values.imag > 0.0))
    real = list(np.flatnonzero(values.imag == 0.0)[np.argsort(-values.real[values.imag == 0.0])])
    while real:
        first = real.pop(0)
        if real:
            similarity = mac(shapes[[first]] * weights, shapes[real] * weights)[0]
            real.pop(int(np.argmax(similarity)))
        chosen.append(first)
    chosen = np.array(chosen)
    return chosen[np.lexsort((-values.real[chosen], np.abs(values.imag[chosen])))]


def state_modes(A: np.ndarray, weights: np.ndarray | None = None) -> Modes:
    """The modes of ``x' = A x`` for a stack ``A`` (s, N, N) whose states are positions then rates.

    ``weights`` (N/2,) scale the position coordinates for the MAC (default ones). The modes of each
    matrix are ordered by frequency (:func:`track` orders them along a speed grid).
    """
    A = np.asarray(A, dtype=float)
    if A.ndim != 3 or A.shape[1] != A.shape[2] or A.shape[1] % 2:
        raise ValueError(f"A has shape {A.shape}: expected a stack (speeds, N, N) with N even "
                         "(positions, then their rates)")
    p = A.shape[1] // 2
    weights = np.ones(p) if weights is None else np.asarray(weights, dtype=float)
    if weights.shape != (p,) or not np.all(weights > 0.0):
        raise ValueError(f"weights of shape {weights.shape}: expected {p} positive numbers, one per "
                         "position coordinate")
    values, vectors = np.linalg.eig(A)
    values = values.astype(complex)
    shapes = np.swapaxes(vectors[:, :p, :], 1, 2).astype(complex)  # (s, N, p)
    picked = np.stack([_representatives(values[k], shapes[k], weights)
                       for k in range(A.shape[0])])
    eigenvalue = np.take_along_axis(values, picked, axis=1)
    shape = _normalised(np.take_along_axis(shapes, picked[..., None], axis=1), weights)
    zero = _zero_tolerance(A)[:, None]
    rigid = np.abs(eigenvalue) <= zero
    divergent = (eigenvalue.imag == 0.0) & ~rigid
    stable = rigid | (eigenvalue.real <= zero)
    return Modes(eigenvalue, shape, divergent, rigid, stable, weights)


def tracking_order(shapes: np.ndarray, frequency: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Order (s, m) of the modes along a speed grid: by frequency at the first speed, then by the
    optimal assignment on ``1 - MAC`` between neighbouring speeds (module docstring)."""
    scaled = shapes * weights
    similarity = mac(scaled[:-1], scaled[1:])  # (s - 1, m, m), untracked indices
    order = np.empty(frequency.shape, dtype=int)
    order[0] = np.argsort(frequency[0], kind="stable")
    for k in range(1, frequency.shape[0]):
        _, columns = linear_sum_assignment(1.0 - similarity[k - 1][order[k - 1]])
        order[k] = columns
    return order


def track(modes: Modes) -> Modes:
    """``modes`` (over a speed grid along the first axis) reordered so that each mode index follows
    one mode through crossings and veering (:func:`tracking_order`)."""
    return modes.take(tracking_order(modes.shape, modes.frequency, modes.weights))


def coordinate_groups(names) -> list[tuple[str, int]]:
    """``(group, k)`` of each position state name: ``theta`` (the hub's, or with a compliant root
    the root's angle) and ``phi`` (the hub's angle with a compliant root) -> ``("hub", 0)``,
    ``q1_3`` -> ``("axial", 3)``, ``q2_1`` -> ``("bending", 1)`` (groups: :data:`GROUPS`)."""
    groups = []
    for name in names:
        prefix, _, index = name.partition("_")
        angle = GROUPS.get(prefix) == "hub" and not index
        modal = prefix in GROUPS and GROUPS[prefix] != "hub" and index.isdigit()
        if not (angle or modal):
            raise ValueError(f"state name {name!r}: expected theta, phi, q1_<k> or q2_<k>")
        groups.append((GROUPS[prefix], int(index) if index else 0))
    return groups


def dominant_content(shapes: np.ndarray, names, weights: np.ndarray, rigid: np.ndarray):
    """Labels and group fractions of mode shapes (..., p) with position state names ``names``.

    Returns ``labels`` (...,) and ``fractions``, a dict group -> (...,) share of ``sum |w_i u_i|^2``
    in that group's coordinates. A ``rigid`` mode (a free hub's rigid-body mode, a held hub's
    prescribed angle) is ``hub``; every other mode is flexible, whatever coordinate dominates it:
    ``axial k`` when the axial coordinates hold more of it than the transverse ones (the bending
    functions with the hub's and root's angles, which turn the beam sideways), else ``bending k``
    (``k`` the dominant function; :func:`numbered_by_frequency` numbers them by frequency).
    """
    coordinates = coordinate_groups(names)
    energy = np.abs(shapes * weights) ** 2
    energy = energy / energy.sum(axis=-1, keepdims=True)
    members = {group: np.array([i for i, (g, _) in enumerate(coordinates) if g == group], dtype=int)
               for group in dict.fromkeys(GROUPS.values())}
    fractions = {group: energy[..., index].sum(axis=-1) for group, index in members.items() if index.size}
    axial = fractions.get("axial", np.zeros(energy.shape[:-1]))
    transverse = fractions.get("bending", 0.0) + fractions.get("hub", 0.0)

    def named(group):  # "<group> k" of the group's dominant function
        index = members[group]
        if not index.size:
            return np.full(energy.shape[:-1], group, dtype=object)
        text = np.array([f"{group} {k}" for _, k in coordinates], dtype=object)
        return text[index[np.argmax(energy[..., index], axis=-1)]]

    labels = np.where(axial > transverse, named("axial"), named("bending"))
    return np.where(np.asarray(rigid, dtype=bool), "hub", labels).astype(str), fractions


def numbered_by_frequency(labels: np.ndarray, frequency: np.ndarray | None = None) -> np.ndarray:
    """``labels`` (..., modes) with each group's modes numbered by frequency: ``bending 1, bending 1,
    axial 1, bending 2`` -> ``bending 1, bending 2, axial 1, bending 3``.

    Without ``frequency`` the modes are taken as ordered by frequency along the last axis; with it
    (the same shape, e.g. tracked modes at each speed) they are ranked by it, ties kept in order.
    The dominant coordinate names a mode well with the hub held; with a free hub whose inertia is
    small against the beam's the hub's rotation puts most of every bending mode's mass-weighted
    content into the first clamped-free function (all would be ``bending 1``), so the rank within
    the group is the name that stays distinct: the k-th bending mode by frequency is ``bending k``.
    """
    out = np.array(labels, dtype=object)
    rank = (np.broadcast_to(np.arange(out.shape[-1]), out.shape) if frequency is None
            else np.argsort(np.argsort(np.asarray(frequency), axis=-1, kind="stable"), axis=-1, kind="stable"))
    for index in np.ndindex(out.shape[:-1]):
        counts: dict[str, int] = {}
        for k in np.argsort(rank[index], kind="stable"):
            group = str(out[index + (k,)]).partition(" ")[0]
            if group and group != "hub":
                counts[group] = counts.get(group, 0) + 1
                out[index + (k,)] = f"{group} {counts[group]}"
    return out.astype(str)
