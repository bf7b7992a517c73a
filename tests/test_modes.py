"""Admissible functions: roots, unit modal mass, boundary conditions, derivatives (notes 6, 7)."""

import numpy as np
import pytest

from hubbeam.model.modes import axial_modes, clamped_free_roots, transverse_modes
from hubbeam.model.parameters import BeamParameters
from hubbeam.model.printed import TABLE1
from hubbeam.model.quadrature import gauss_legendre

PARAMS = BeamParameters(**TABLE1)
N = 20
RHO_A = PARAMS.rho * PARAMS.A


def test_roots_solve_the_frequency_equation_to_double_precision():
    z = clamped_free_roots(N)
    # 1 + cos z cosh z = 0 divided by cosh z; |d/dz (cos z + sech z)| ~ 1 at the roots, so a
    # residual below two ulps of z means z is within about two ulps of the exact root
    assert np.all(np.abs(np.cos(z) + 1.0 / np.cosh(z)) <= 2.0 * np.spacing(z))
    # tabulated values (Blevins, Formulas for natural frequency and mode shape, Table 8-1)
    published = [1.87510406871, 4.69409113297, 7.85475743823, 10.9955407349, 14.1371683910]
    np.testing.assert_allclose(z[:5], published, rtol=1e-11)
    assert np.all(np.diff(z) > 2.5)
    np.testing.assert_allclose(z[10:], (2 * np.arange(11, N + 1) - 1) * np.pi / 2, rtol=1e-15)


@pytest.mark.parametrize("family", [transverse_modes, axial_modes])
def test_unit_modal_mass_for_20_modes(family):
    x, w = gauss_legendre(200, 0.0, PARAMS.L)
    f = family(x, N, PARAMS)
    mass = RHO_A * (f.T * w) @ f
    assert np.max(np.abs(mass - np.eye(N))) < 1e-13


def test_clamped_free_boundary_conditions_for_20_modes():
    beta = clamped_free_roots(N) / PARAMS.L
    scale = 1.0 / np.sqrt(RHO_A * PARAMS.L)
    for derivative, x in [(0, 0.0), (1, 0.0), (2, PARAMS.L), (3, PARAMS.L)]:
        value = transverse_modes(x, N, PARAMS, derivative)[0]
        assert np.max(np.abs(value) / (scale * beta**derivative)) < 1e-13, derivative
    # and the functions are of order one elsewhere (no overflow, no cancellation to zero)
    tip = transverse_modes(PARAMS.L, N, PARAMS)[0] / scale
    np.testing.assert_allclose(np.abs(tip), 2.0, rtol=1e-12)
    a = (2 * np.arange(1, N + 1) - 1) * np.pi / (2 * PARAMS.L)
    assert np.max(np.abs(axial_modes(0.0, N, PARAMS)[0])) == 0.0
    assert np.max(np.abs(axial_modes(PARAMS.L, N, PARAMS, 1)[0]) / a) < 1e-13 * scale


@pytest.mark.parametrize("family, orders", [(transverse_modes, 3), (axial_modes, 1)])
def test_derivatives_integrate_back_to_the_functions(family, orders):
    """int_0^x f^(k+1) = f^(k)(x) - f^(k)(0) at arbitrary x, for every mode."""
    x = np.array([0.37, 2.9, 5.5, 8.0])
    nodes, weights = gauss_legendre(120, np.zeros_like(x), x)
    for k in range(orders):
        derivative = family(nodes.ravel(), N, PARAMS, k + 1).reshape(nodes.shape + (N,))
        integral = np.einsum("mq,mqi->mi", weights, derivative)
        change = family(x, N, PARAMS, k) - family(0.0, N, PARAMS, k)
        scale = np.max(np.abs(family(np.linspace(0, PARAMS.L, 401), N, PARAMS, k)), axis=0)
        assert np.max(np.abs(integral - change) / scale) < 1e-12, k


def test_eigenfunction_property_fourth_derivative():
    """f2'''' = beta^4 f2: checked as int_x^L f2''' ... via (f2'''(L) - f2'''(x)) = beta^4 int_x^L f2."""
    beta = clamped_free_roots(N) / PARAMS.L
    x = np.array([0.0, 1.3, 4.0, 7.1])
    nodes, weights = gauss_legendre(120, x, np.full_like(x, PARAMS.L))
    f = transverse_modes(nodes.ravel(), N, PARAMS).reshape(nodes.shape + (N,))
    integral = beta**4 * np.einsum("mq,mqi->mi", weights, f)
    change = transverse_modes(PARAMS.L, N, PARAMS, 3) - transverse_modes(x, N, PARAMS, 3)
    scale = beta**3 / np.sqrt(RHO_A * PARAMS.L)
    assert np.max(np.abs(integral - change) / scale) < 1e-12


@pytest.mark.parametrize("bad", [dict(n_modes=0), dict(n_modes=21), dict(derivative=4)])
def test_bad_requests_name_the_argument(bad):
    kwargs = dict(n_modes=5, derivative=0) | bad
    with pytest.raises(ValueError, match=next(iter(bad))):
        transverse_modes([1.0], kwargs["n_modes"], PARAMS, kwargs["derivative"])
