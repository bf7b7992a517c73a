"""System matrices (Eqs. 13-20, Appendix A1-A10): closed forms, quadrature convergence, tip mass."""

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson

from hubbeam.model.matrices import (
    S_matrix,
    SystemMatrices,
    assemble,
    configuration_name,
    from_dataset,
    to_dataset,
)
from hubbeam.model.modes import axial_modes, clamped_free_roots, transverse_modes
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.printed import TABLE1
from hubbeam.model.quadrature import effective_points

PARAMS = BeamParameters(**TABLE1)
RHO_A = PARAMS.rhoA
MATRIX_FIELDS = ("Jb", "K1", "K2", "M1", "M2", "V1", "V2", "D", "R", "SL")
INTERIOR_TIP = TipMass(mass=0.5, position=5.3)


def relative_difference(a, b):
    return np.max(np.abs(np.asarray(a) - b)) / np.max(np.abs(b))


@pytest.mark.parametrize("n_modes", [5, 20])
@pytest.mark.parametrize("tip", [None, INTERIOR_TIP])
def test_matrices_converged_under_quadrature_refinement(n_modes, tip):
    assert_converged_in_quadrature_points(PARAMS, tip, n_modes)


def assert_converged_in_quadrature_points(params, tip, n_modes):
    """Every matrix of ``assemble`` within 1e-12 of the same with three times the Gauss nodes."""
    coarse = assemble(params, tip, n_modes)
    fine = assemble(params, tip, n_modes, n_quad=3 * effective_points(64, n_modes))
    for name in MATRIX_FIELDS:
        assert relative_difference(getattr(coarse, name), getattr(fine, name)) < 1e-12, name


def test_contract_shapes_and_point_cloud():
    n = 5
    sm = assemble(PARAMS, INTERIOR_TIP, n)
    nq = effective_points(64, n)
    assert isinstance(sm, SystemMatrices)
    for name in ("Jh", "Jb", "rA"):
        assert np.shape(getattr(sm, name)) == ()
    for name in ("K1", "K2", "M1", "M2", "D", "R", "SL"):
        assert getattr(sm, name).shape == (n, n)
    for name in ("V1", "V2", "f1L", "f2L"):
        assert getattr(sm, name).shape == (n,)
    assert sm.x.shape == sm.w.shape == (nq + 1,)
    assert sm.F1.shape == sm.F2.shape == (nq + 1, n)
    assert sm.S.shape == (nq + 1, n, n)
    assert sm.x[-1] == INTERIOR_TIP.position and sm.w[-1] == INTERIOR_TIP.mass
    np.testing.assert_allclose(sm.w[:-1].sum(), RHO_A * PARAMS.L, rtol=1e-14)
    bare = assemble(PARAMS, None, n)
    assert bare.w[-1] == 0.0 and bare.x[-1] == PARAMS.L


def test_closed_forms_of_the_bare_beam():
    """K1, K2, M1, M2, Jb, V1, V2 against integrals done by hand for the chosen modes."""
    n = 20
    sm = assemble(PARAMS, None, n)
    beta = clamped_free_roots(n) / PARAMS.L
    a = (2 * np.arange(1, n + 1) - 1) * np.pi / (2 * PARAMS.L)
    np.testing.assert_allclose(sm.K2, np.diag(PARAMS.E * PARAMS.I * beta**4 / RHO_A),
                               rtol=0, atol=1e-13 * sm.K2.max())
    np.testing.assert_allclose(sm.K1, np.diag(PARAMS.E / PARAMS.rho * a**2),
                               rtol=0, atol=1e-13 * sm.K1.max())
    np.testing.assert_allclose(sm.M1, np.eye(n), atol=1e-13)
    np.testing.assert_allclose(sm.M2, np.eye(n), atol=1e-13)
    rA, L = PARAMS.rA, PARAMS.L
    np.testing.assert_allclose(sm.Jb, RHO_A * ((rA + L) ** 3 - rA**3) / 3, rtol=1e-14)
    # int (rA + x) sin(a x) dx with cos(aL) = 0, sin(aL) = (-1)^(i+1)
    sign = (-1.0) ** np.arange(n)
    V1 = np.sqrt(2 * RHO_A / L) * (rA / a + sign / a**2)
    assert relative_difference(sm.V1, V1) < 1e-13
    # f2'''' = beta^4 f2 and the boundary conditions give int f2 = -f2'''(0) / beta^4 and
    # int x f2 = f2''(0) / beta^4
    d2, d3 = (transverse_modes(0.0, n, PARAMS, k)[0] for k in (2, 3))
    assert relative_difference(sm.V2, RHO_A * (-rA * d3 + d2) / beta**4) < 1e-13


def test_S_against_a_brute_force_cumulative_integral():
    n = 12
    x = np.linspace(0.0, PARAMS.L, 16001)
    slopes = transverse_modes(x, n, PARAMS, derivative=1)
    brute = cumulative_simpson(slopes[:, :, None] * slopes[:, None, :], x=x, axis=0, initial=0)
    picks = np.arange(0, x.size, 800)
    S = S_matrix(PARAMS, x[picks], n)
    assert relative_difference(S, brute[picks]) < 1e-10
    np.testing.assert_array_equal(S[0], 0.0)


def test_D_equals_the_nested_point_cloud_integral():
    """Swapped single integral (beam part of D) against sum_k w_k (rA + x_k) S(x_k)."""
    for tip in (None, INTERIOR_TIP):
        sm = assemble(PARAMS, tip, 20)
        nested = np.einsum("k,kij->ij", sm.w * (sm.rA + sm.x), sm.S)
        assert relative_difference(sm.D, nested) < 1e-13


def test_matrices_are_point_cloud_sums():
    """The point cloud integrates the mass matrices exactly as assembled (used by eom.py)."""
    sm = assemble(PARAMS, INTERIOR_TIP, 8)
    lever = sm.rA + sm.x
    assert relative_difference(sm.Jb, sm.w @ lever**2) < 1e-14
    assert relative_difference(sm.M1, (sm.F1.T * sm.w) @ sm.F1) < 1e-14
    assert relative_difference(sm.M2, (sm.F2.T * sm.w) @ sm.F2) < 1e-14
    assert relative_difference(sm.V1, (sm.w * lever) @ sm.F1) < 1e-14
    assert relative_difference(sm.V2, (sm.w * lever) @ sm.F2) < 1e-14
    assert relative_difference(sm.R, (sm.F1.T * sm.w) @ sm.F2) < 1e-14


@pytest.mark.parametrize("tip", [None, TipMass(0.1, 8.0), INTERIOR_TIP, TipMass(3.0, 0.7)])
def test_D_and_S_symmetric_non_negative_definite(tip):
    sm = assemble(PARAMS, tip, 10)
    for matrix in (sm.D, sm.SL, *sm.S):
        np.testing.assert_array_equal(matrix, matrix.T)
        assert np.linalg.eigvalsh(matrix).min() >= -1e-13 * np.abs(matrix).max()
    assert np.linalg.eigvalsh(sm.D).min() > 0.0  # D is even positive definite (f2' independent)


@pytest.mark.parametrize("mass", [0.1, 0.5])
def test_tip_terms_reproduce_the_appendix_at_the_beam_tip(mass):
    """l = L: the tip-mass increments are Eqs. (A1)-(A10) with (rA + L) and S(L)."""
    n = 5
    bare = assemble(PARAMS, None, n)
    loaded = assemble(PARAMS, TipMass(mass, PARAMS.L), n)
    lever = PARAMS.rA + PARAMS.L
    f1, f2 = bare.f1L, bare.f2L
    expected = {
        "Jb": mass * lever**2,  # (A1), q-independent part
        "M1": mass * np.outer(f1, f1),  # (A4)
        "M2": mass * np.outer(f2, f2),  # (A5)
        "V1": mass * lever * f1,  # (A1) 2 m_t (rA + L) f1 q1, (A10)
        "V2": mass * lever * f2,  # (A3)
        "R": mass * np.outer(f1, f2),  # (A2), (A6)
        "D": mass * lever * bare.SL,  # (A1), (A8), (A9)
    }
    for name, value in expected.items():
        increment = getattr(loaded, name) - getattr(bare, name)
        assert relative_difference(increment, value) < 1e-12, name
    for name in ("K1", "K2"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(bare, name))
    np.testing.assert_allclose(loaded.F2[-1], bare.f2L, rtol=1e-15)
    np.testing.assert_allclose(loaded.S[-1], bare.SL, rtol=1e-14, atol=1e-14 * bare.SL.max())


def test_interior_tip_mass_uses_its_own_position():
    tip = INTERIOR_TIP
    n = 5
    increment = assemble(PARAMS, tip, n).M2 - assemble(PARAMS, None, n).M2
    f2 = transverse_modes(tip.position, n, PARAMS)[0]
    assert relative_difference(increment, tip.mass * np.outer(f2, f2)) < 1e-12
    D_increment = assemble(PARAMS, tip, n).D - assemble(PARAMS, None, n).D
    S_l = S_matrix(PARAMS, tip.position, n)[0]
    assert relative_difference(D_increment, tip.mass * (PARAMS.rA + tip.position) * S_l) < 1e-12


def test_first_rows_are_leading_blocks():
    """Matrices for n modes are the leading blocks of those for more modes."""
    small, large = assemble(PARAMS, INTERIOR_TIP, 3), assemble(PARAMS, INTERIOR_TIP, 12)
    for name in ("K2", "M2", "D", "R"):
        assert relative_difference(getattr(small, name), getattr(large, name)[:3, :3]) < 1e-13
    np.testing.assert_allclose(axial_modes(PARAMS.L, 3, PARAMS)[0], small.f1L, rtol=1e-15)


@pytest.mark.parametrize(
    "tip, key",
    [(TipMass(0.1, 8.5), "tip_mass.position"), (TipMass(-1.0, 8.0), "tip_mass.mass"),
     (TipMass(float("nan"), 8.0), "tip_mass.mass")],
)
def test_bad_tip_mass_names_the_key(tip, key):
    with pytest.raises(ValueError, match=key.replace(".", r"\.")):
        assemble(PARAMS, tip, 3)


def test_dataset_round_trip_and_names():
    sm = assemble(PARAMS, TipMass(0.1, 8.0), 4)
    ds = to_dataset(sm, PARAMS, TipMass(0.1, 8.0), n_quad_requested=64)
    for name in ds.variables:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
    assert list(ds["mode"].values) == [1, 2, 3, 4]
    assert ds.attrs["configuration"] == "mt0p1_l8"
    back = from_dataset(ds)
    for name, value in sm._asdict().items():
        np.testing.assert_array_equal(getattr(back, name), value)
    assert configuration_name(None) == "mt0"
    assert configuration_name(TipMass(0.0, 3.0)) == "mt0"
    assert configuration_name(TipMass(0.5, 7.5)) == "mt0p5_l7p5"
