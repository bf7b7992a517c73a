"""Damping of the elastic coordinates of a case: the damping matrices ``C1, C2``.

A case's optional ``damping`` mapping acts on the axial block ``q1`` (mass ``M1``, stiffness
``K1``, Eqs. 14, 16) and the transverse block ``q2`` (``M2``, ``K2``, Eqs. 15, 16) separately; the
damping forces ``-C1 q1'`` and ``-C2 q2'`` join the elastic rows of Eq. (24):

* ``{kind: modal, axial: zeta1, transverse: zeta2}``: the damping ratio of every mode of the block,
  ``0 <= zeta < 1``: ``C = M Phi diag(2 zeta omega_i) Phi^T M`` with the eigenpairs
  ``K phi_i = omega_i^2 M phi_i`` of the non-rotating block, ``Phi^T M Phi = I`` (so that
  ``Phi^T C Phi = diag(2 zeta omega_i)``, valid for a non-diagonal ``M`` with a tip mass too);
* ``{kind: rayleigh, mass_coefficient: alpha, stiffness_coefficient: beta}`` (s-1, s; >= 0):
  ``C = alpha M + beta K`` per block.

The transverse block's mass is ``M2`` with a tip body's rotary inertia (``transverse_mass``).

No ``damping`` (or ``None``) gives zero matrices: the undamped equations, bit for bit. The keys
and ranges of each kind are checked with the configuration (schema ``damping``).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.linalg import eigh

from hubbeam.core.system_matrices import transverse_mass


def modal_damping(M: np.ndarray, K: np.ndarray, ratio: float) -> np.ndarray:
    """``M Phi diag(2 ratio omega_i) Phi^T M`` from the mass-normalised eigenpairs of ``(K, M)``."""
    omega2, phi = eigh(K, M)
    mphi = M @ phi
    return (mphi * (2.0 * ratio * np.sqrt(np.clip(omega2, 0.0, None)))) @ mphi.T


def damping_matrices(damping: Mapping | None, sm) -> np.ndarray:
    """``C = [C1, C2]`` (shape ``(2, n, n)``) of a checked ``damping`` for SystemMatrices ``sm``."""
    n = np.shape(sm.M1)[0]
    C = np.zeros((2, n, n))
    if damping is None:
        return C
    blocks = ((sm.M1, sm.K1), (transverse_mass(sm), sm.K2))
    if damping["kind"] == "modal":
        for b, (ratio, (M, K)) in enumerate(zip((damping["axial"], damping["transverse"]), blocks)):
            C[b] = modal_damping(np.asarray(M), np.asarray(K), float(ratio))
    else:
        alpha, beta = float(damping["mass_coefficient"]), float(damping["stiffness_coefficient"])
        for b, (M, K) in enumerate(blocks):
            C[b] = alpha * np.asarray(M) + beta * np.asarray(K)
    return np.ascontiguousarray(C)
