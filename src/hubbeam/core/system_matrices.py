"""The system matrices every kernel reads, as one numba-friendly namedtuple type.

Defined in the core so that jitted code can build it (``core.sweep.matrices_at``) without
importing the rest of the package; :func:`hubbeam.model.matrices.assemble` fills it (Eqs. 13-20 and the
tip-mass terms of the Appendix).

The tip body (``hubbeam.model.parameters.TipMass``, ``docs/tip-body.md``) enters twice. Its mass
is the last point of the point cloud, at its centre of mass, and is summed into ``Jb``, ``M1``,
``M2``, ``V1``, ``V2``, ``D``, ``R`` like every other mass point. Its rotary inertia ``Jt`` about
that centre turns with the hub and the beam's slope ``v'(l) = dF2t . q2`` at the attachment: it
adds ``Jt (theta' + dF2t . q2')^2 / 2`` to the kinetic energy, a constant block of the mass matrix
that the fields leave out (``M2`` also carries the centrifugal terms ``theta'^2 q2^T M2 q2 / 2``
of the translating masses, which the rotation lacks) and :func:`rotary_mass` gives.
"""

from typing import NamedTuple

import numpy as np


class SystemMatrices(NamedTuple):
    """Matrices of Eqs. (13)-(20) with the tip-mass terms, plus the point cloud (numba-friendly).

    ``n`` modes, ``nq`` Gauss nodes, point cloud of ``nq + 1`` points whose last one is the tip
    mass (weight ``m_t``, zero when there is none). See ``docs/architecture.md``.
    """

    Jh: float  # hub inertia, kg m2
    Jb: float  # (13) + m_t (rA + l)^2, kg m2
    K1: np.ndarray  # (n, n) (14), s-2
    K2: np.ndarray  # (n, n) (15), s-2
    M1: np.ndarray  # (n, n) (16) incl. tip mass, 1
    M2: np.ndarray  # (n, n) (16) incl. tip mass, 1
    V1: np.ndarray  # (n,) (17) incl. tip mass, kg1/2 m
    V2: np.ndarray  # (n,) (17) incl. tip mass, kg1/2 m
    D: np.ndarray  # (n, n) (18) incl. m_t (rA + l) S(l), 1
    R: np.ndarray  # (n, n) (19) incl. m_t f1(l)^T f2(l), 1
    rA: float  # hub radius, m
    x: np.ndarray  # (nq + 1,) point-cloud abscissae, m
    w: np.ndarray  # (nq + 1,) point-cloud masses, kg
    F1: np.ndarray  # (nq + 1, n) f1 at the points, kg-1/2
    F2: np.ndarray  # (nq + 1, n) f2 at the points, kg-1/2
    S: np.ndarray  # (nq + 1, n, n) S(x) at the points, kg-1 m-1
    f1L: np.ndarray  # (n,) f1(L), kg-1/2
    f2L: np.ndarray  # (n,) f2(L), kg-1/2
    SL: np.ndarray  # (n, n) S(L), kg-1 m-1
    Jt: float  # rotary inertia of the tip body about its centre, kg m2
    dF2t: np.ndarray  # (n,) f2'(l), the slope at the tip body's attachment, kg-1/2 m-1


def rotary_mass(sm):
    """The tip body's rotary inertia in the mass matrix of ``y = (theta, q1, q2)``: its hub entry
    ``Jt``, its hub-``q2`` coupling ``Jt f2'(l)`` and its ``q2``-``q2`` block
    ``Jt f2'(l)^T f2'(l)`` (the Hessian in the rates of ``Jt (theta' + f2'(l) q2')^2 / 2``).

    Exact zeros for a body without rotary inertia (the point tip mass), so that adding them changes
    no value."""
    g = np.asarray(sm.dF2t, dtype=float)
    Jt = float(sm.Jt)
    return Jt, Jt * g, Jt * np.multiply.outer(g, g)


def transverse_mass(sm):
    """The ``q2``-``q2`` block of the mass matrix: ``M2`` (the translating masses, Eq. 16) plus the
    tip body's rotary inertia ``Jt f2'(l)^T f2'(l)``; ``M2`` itself when ``Jt = 0``."""
    if float(sm.Jt) == 0.0:
        return sm.M2
    return sm.M2 + rotary_mass(sm)[2]
