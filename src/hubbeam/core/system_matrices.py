"""The system matrices every kernel reads, as one numba-friendly namedtuple type.

Defined in the core so that jitted code can build it (``core.sweep.matrices_at``) without
importing the rest of the package; :func:`hubbeam.model.matrices.assemble` fills it (Eqs. 13-20 and the
tip-mass terms of the Appendix).
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
