"""CFOAM from pre-contracted tensors (``core.cfoam_tensors``) against the point-cloud kernel.

``cfoam_system`` must give the same ``M`` and ``F`` as ``eom._cfoam_system`` (which
``tests/test_eom.py`` checks against Lagrange's equations of the exact kinetic energy) for the
assembled matrices of Table 1, with and without a tip mass, at realistic and at large amplitudes.
Differences are measured against the size of the terms summed: ``|M_ij| <= sqrt(M_ii M_jj)`` for
an SPD matrix, and by Cauchy-Schwarz the inertial force ``sum_k w_k J_ki b_k`` is at most
``sqrt(M_ii) sqrt(sum_k w_k |b_k|^2)``, with ``b`` the velocity-only acceleration of
``docs/cfoam.md`` evaluated here independently.
"""

import numpy as np
import pytest

from hubbeam.core import eom
from hubbeam.core.cfoam_tensors import cfoam_system, cfoam_tensors
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.printed import TABLE1
from hubbeam.simulation.simulate import kernel_matrices

PARAMS = BeamParameters(**TABLE1)
TIPS = {"none": None, "tip": TipMass(0.5, PARAMS.L), "interior": TipMass(0.5, 6.0)}
RTOL = 1e-12


def _matrices(n, tip):
    return kernel_matrices(assemble(PARAMS, TIPS[tip], n))


def _state(rng, n, amplitude):
    """Random (y, v): modal amplitudes falling with the mode number; 'large' means transverse
    deflections of a good fraction of L (f2(L) ~ 1.6 kg^-1/2) and fast rates."""
    k = np.arange(1, n + 1)
    if amplitude == "realistic":
        scales = (1.0, 1e-4 / k, 0.05 / k**2, 2.0, 1e-3 / k, 0.5 / k)
    else:
        scales = (1.0, 0.05 / k, 1.0 / k, 5.0, 0.5 / k, 5.0 / k)
    parts = [s * rng.normal(size=np.shape(s) or 1) for s in scales]
    return np.concatenate(parts[:3]), np.concatenate(parts[3:])


def _velocity_only_acceleration_norm(sm, y, v):
    """sqrt(sum_k w_k |b_k|^2), b = (-q2'^T S q2' - 2 thd Y' - thd^2 X, 2 thd X' - thd^2 Y)."""
    n = sm.M1.shape[0]
    q1, q2 = y[1 : 1 + n], y[1 + n :]
    thd, q1d, q2d = v[0], v[1 : 1 + n], v[1 + n :]
    Sq2 = np.einsum("kij,j->ki", sm.S, q2)
    X = sm.rA + sm.x + sm.F1 @ q1 - 0.5 * Sq2 @ q2
    Y = sm.F2 @ q2
    Xd = sm.F1 @ q1d - Sq2 @ q2d
    Yd = sm.F2 @ q2d
    g = np.einsum("i,kij,j->k", q2d, sm.S, q2d)
    bx = -g - 2 * thd * Yd - thd**2 * X
    by = 2 * thd * Xd - thd**2 * Y
    return np.sqrt(np.sum(sm.w * (bx**2 + by**2)))


def _both(sm, ct, y, v, tau):
    N = y.size
    M_cloud, F_cloud, M_tensor, F_tensor = (np.empty((N, N)), np.empty(N), np.empty((N, N)),
                                            np.empty(N))
    eom._cfoam_system(y, v, tau, sm, M_cloud, F_cloud)
    cfoam_system(y, v, tau, ct, M_tensor, F_tensor)
    return M_cloud, F_cloud, M_tensor, F_tensor


@pytest.mark.parametrize("n", [1, 3, 5, 8])
@pytest.mark.parametrize("tip", sorted(TIPS))
@pytest.mark.parametrize("amplitude", ["realistic", "large"])
def test_tensor_kernel_equals_point_cloud_kernel(n, tip, amplitude):
    sm = _matrices(n, tip)
    # without the stiffness the force is purely inertial and the comparison sharper
    stiffless = sm._replace(K1=np.zeros_like(sm.K1), K2=np.zeros_like(sm.K2))
    rng = np.random.default_rng([n, len(tip), len(amplitude)])
    for matrices in (sm, stiffless):
        ct = cfoam_tensors(matrices)
        K = np.zeros((2 * n + 1, 2 * n + 1))
        K[1 : 1 + n, 1 : 1 + n] = matrices.K1
        K[1 + n :, 1 + n :] = matrices.K2
        for _ in range(4):
            y, v = _state(rng, n, amplitude)
            tau = 100.0 * rng.normal()
            M_cloud, F_cloud, M_tensor, F_tensor = _both(matrices, ct, y, v, tau)
            diag = np.sqrt(np.diag(M_cloud))
            assert np.all(np.abs(M_tensor - M_cloud) <= RTOL * np.outer(diag, diag))
            scale = (diag * _velocity_only_acceleration_norm(matrices, y, v)
                     + np.abs(K) @ np.abs(y))
            scale[0] += abs(tau)
            assert np.all(np.abs(F_tensor - F_cloud) <= RTOL * scale)


@pytest.mark.parametrize("tip", sorted(TIPS))
def test_mass_matrix_is_symmetric_positive_definite(tip):
    n = 5
    sm = _matrices(n, tip)
    ct = cfoam_tensors(sm)
    rng = np.random.default_rng(7)
    for amplitude in ("realistic", "large"):
        for _ in range(4):
            y, v = _state(rng, n, amplitude)
            _, _, M, _ = _both(sm, ct, y, v, 0.0)
            np.testing.assert_array_equal(M, M.T)
            assert np.linalg.eigvalsh(M)[0] > 0.0


@pytest.mark.parametrize("tip", sorted(TIPS))
def test_low_order_sums_are_the_integrals_of_eqs_13_to_19(tip):
    """The point-cloud sums in the tensors equal Jb, V1, V2, M1, M2, R, D assembled from their
    integrals (D by a different quadrature, the order of integration swapped)."""
    sm = _matrices(5, tip)
    ct = cfoam_tensors(sm)
    assert ct.Jb == pytest.approx(sm.Jb, rel=RTOL)
    # mats: M1, M2, K1, K2 (copied), then the sums M1c, M2c, R, D
    for ours, assembled in zip([*ct.vecs, *ct.mats], [sm.V1, sm.V2, sm.M1, sm.M2, sm.K1, sm.K2,
                                                      sm.M1, sm.M2, sm.R, sm.D]):
        np.testing.assert_allclose(ours, assembled, rtol=0, atol=RTOL * np.abs(assembled).max())


def test_non_symmetric_foreshortening_matrix_is_rejected():
    sm = _matrices(3, "none")
    S = sm.S.copy()
    S[10, 0, 1] *= 1.01
    with pytest.raises(ValueError, match="SystemMatrices.S"):
        cfoam_tensors(sm._replace(S=S))
