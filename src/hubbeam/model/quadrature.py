"""Gauss-Legendre quadrature on beam intervals and the point cloud of the mass distribution.

Every beam integral of the paper (Eqs. 13-20) is evaluated by an ``n``-point Gauss-Legendre rule
on ``[0, L]`` (:func:`beam_rule`). A beam with tabulated sections (``hubbeam.model.beam``) has
properties with kinks at its stations; there the rule is composite, one Gauss rule per segment
between stations, so that each rule integrates a smooth integrand. The *point cloud* is the
discrete mass distribution that these rules integrate against: the Gauss nodes carrying the
masses ``rho A(x_k) w_k``, followed by the tip mass ``m_t`` at ``x = l`` (every ``int (.) rho A dx``
gains ``m_t (.)(l)``).
"""

from functools import lru_cache

import numpy as np

from hubbeam.model.limits import MAX_QUADRATURE_POINTS, MIN_QUADRATURE_POINTS

#: Fewest nodes on one segment of a composite rule (short segments between close stations).
MIN_SEGMENT_POINTS = 4


@lru_cache(maxsize=32)
def _reference_rule(n_points):
    nodes, weights = np.polynomial.legendre.leggauss(n_points)
    nodes.flags.writeable = False
    weights.flags.writeable = False
    return nodes, weights


def gauss_legendre(n_points, a, b):
    """Nodes and weights of the ``n_points``-point Gauss-Legendre rule on ``[a, b]``.

    ``a`` and ``b`` may be arrays of equal shape ``s``; the result then has shape ``s + (n,)``
    (one rule per interval).
    """
    if not isinstance(n_points, (int, np.integer)) or not 1 <= n_points <= MAX_QUADRATURE_POINTS:
        raise ValueError(f"n_points = {n_points!r}: expected an integer in 1..{MAX_QUADRATURE_POINTS}")
    t, w = _reference_rule(int(n_points))
    a = np.asarray(a, dtype=float)[..., None]
    b = np.asarray(b, dtype=float)[..., None]
    half = 0.5 * (b - a)
    return a + half * (t + 1.0), half * w


def effective_points(n_quad, n_modes):
    """Number of Gauss nodes actually used: ``max(n_quad, 30 + 3 n_modes)``.

    The most oscillatory integrands (``f2_i'' f2_j''`` in K2, ``f2_i' f2_j'`` in D and S) contain
    ``cos(2 beta_n x)`` with ``beta_n L ~ (2n - 1) pi / 2``, i.e. about ``n`` periods on the beam;
    an N-point Gauss rule is exact to polynomial degree 2N - 1 and integrates them to machine
    precision once N exceeds ``beta_n L / 2`` by a margin (measured: 20 nodes for 5 modes, 50 for
    20 modes reach 1e-13). The floor ``30 + 3 n_modes`` (45 for 5 modes, 90 for 20) keeps every
    matrix converged to 1e-12 relative with a wide margin (tests/test_matrices.py shows it),
    whatever is configured; the configured ``n_quad`` (``numerics.quadrature_points``, 64) is
    used when larger.
    """
    if not isinstance(n_quad, (int, np.integer)) or not MIN_QUADRATURE_POINTS <= n_quad <= MAX_QUADRATURE_POINTS:
        raise ValueError(
            f"numerics.quadrature_points = {n_quad!r}: expected an integer in "
            f"{MIN_QUADRATURE_POINTS}..{MAX_QUADRATURE_POINTS}"
        )
    return int(max(n_quad, 30 + 3 * n_modes))


def segment_points(n_points, stations):
    """Gauss nodes per segment between consecutive ``stations`` for a composite rule of
    ``n_points`` nodes in all.

    The admissible functions oscillate uniformly along the beam, so each segment gets its share
    of the nodes by length (largest remainders rounded up, so the counts add up to ``n_points``),
    and at least ``MIN_SEGMENT_POINTS``. A single segment gets exactly ``n_points``.
    """
    lengths = np.diff(np.asarray(stations, dtype=float))
    share = n_points * lengths / lengths.sum()
    counts = np.floor(share).astype(int)
    counts[np.argsort(counts - share)[: n_points - counts.sum()]] += 1
    return np.maximum(counts, MIN_SEGMENT_POINTS).tolist()


def beam_rule(params, n_points):
    """Nodes (m) and plain weights (m) of the quadrature on ``[0, L]``, broken at the stations.

    One Gauss-Legendre rule per segment between consecutive ``params.stations``, with
    :func:`segment_points` nodes; for a uniform beam (stations ``0, L``) this is the
    ``n_points`` rule on ``[0, L]``.
    """
    stations = params.stations
    rules = [gauss_legendre(n, a, b) for n, a, b
             in zip(segment_points(n_points, stations), stations[:-1], stations[1:])]
    return (np.concatenate([nodes for nodes, _ in rules]),
            np.concatenate([weights for _, weights in rules]))


def point_cloud(params, mass, position, n_points):
    """Abscissae and masses of the discrete mass distribution (beam nodes, then the tip).

    Beam nodes of :func:`beam_rule` with masses ``rho A(x_k) w_k``. Returns ``x`` (m) and ``w``
    (kg), of shape ``(n_points + 1,)`` (more when short segments need their minimum of nodes);
    the last entry is the tip mass ``mass`` at ``position`` (zero when there is none).
    """
    x, w = beam_rule(params, n_points)
    return (
        np.append(x, float(position)),
        np.append(params.rhoA_at(x) * w, float(mass)),
    )
