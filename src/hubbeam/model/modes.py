"""Admissible functions of the assumed-mode discretisation (Eq. 11; reproduction notes 6 and 7).

* Transverse deflection ``w2 = f2(x) q2``: clamped-free Euler-Bernoulli eigenfunctions
  ``cosh(b x) - cos(b x) - s_i (sinh(b x) - sin(b x))`` with ``b = beta_i`` and ``beta_i L`` the
  roots of ``1 + cos z cosh z = 0``.
* Axial deformation ``w1 = f1(x) q1``: clamped-free rod modes ``sin((2i - 1) pi x / 2L)``.

Both families are scaled to unit modal mass of the bare beam, ``int_0^L rho A f_i f_j dx =
delta_ij`` (units kg^-1/2), so that ``M1 = M2 = I`` without a tip mass. For a non-uniform beam
(``hubbeam.model.beam.BeamSections``) the same functions of the uniform beam of the same length serve
as a Ritz basis, scaled to unit modal mass of the uniform beam of the same total mass,
``rho A_ref = m_beam / L`` (``params.rhoA_ref``); ``M1`` and ``M2`` are then not diagonal.

The textbook form of the beam function subtracts two numbers of size ``e^{beta L}`` to obtain a
number of order one, which loses every digit by the 12th mode or so. Here it is rewritten as

    phi(z) = c_plus e^{z - Z} + c_minus e^{-z} - cos z + s sin z,      z = beta x, Z = beta L,

with ``c_plus = (1 - s) e^Z / 2`` and ``c_minus = (1 + s) / 2`` computed from closed forms that
only involve ``e^{-Z}``; every term is then bounded by a small constant on ``0 <= x <= L`` and no
exponential can overflow.
"""

import numpy as np

from hubbeam.model.limits import MAX_MODES, MIN_MODES

#: Derivatives of cos and sin of order k (mod 4) as (sign, function) pairs.
_COS_DERIVATIVES = ((1.0, np.cos), (-1.0, np.sin), (-1.0, np.cos), (1.0, np.sin))
_SIN_DERIVATIVES = ((1.0, np.sin), (1.0, np.cos), (-1.0, np.sin), (-1.0, np.cos))

MAX_DERIVATIVE = 3


def _check_request(n_modes, derivative):
    if not isinstance(n_modes, (int, np.integer)) or not MIN_MODES <= n_modes <= MAX_MODES:
        raise ValueError(f"n_modes = {n_modes!r}: expected an integer in {MIN_MODES}..{MAX_MODES}")
    if not isinstance(derivative, (int, np.integer)) or not 0 <= derivative <= MAX_DERIVATIVE:
        raise ValueError(
            f"derivative = {derivative!r}: expected an integer in 0..{MAX_DERIVATIVE}"
        )


def _sech(z):
    """1 / cosh z without overflow for large z."""
    e = np.exp(-np.abs(z))
    return 2.0 * e / (1.0 + e * e)


def clamped_free_roots(n_modes):
    """The first ``n_modes`` positive roots ``beta_i L`` of ``1 + cos z cosh z = 0``.

    The equation is solved in the overflow-free form ``cos z + sech z = 0`` by Newton's method
    started from the asymptotic root ``(2i - 1) pi / 2``; iteration stops when the step is below
    a few ulps, so the roots are accurate to double precision.
    """
    _check_request(n_modes, 0)
    z = (2.0 * np.arange(1, n_modes + 1) - 1.0) * np.pi / 2.0
    for _ in range(60):
        sech = _sech(z)
        step = (np.cos(z) + sech) / (-np.sin(z) - sech * np.tanh(z))
        z = z - step
        if np.all(np.abs(step) <= 4.0 * np.finfo(float).eps * z):
            return z
    raise RuntimeError("Newton iteration for the clamped-free roots did not converge")


def _beam_coefficients(Z):
    """Coefficients ``s``, ``c_plus``, ``c_minus`` of the stable form, from ``e^{-Z}`` only."""
    e = np.exp(-Z)
    den = 1.0 - e * e + 2.0 * e * np.sin(Z)  # 2 e^{-Z} (sinh Z + sin Z)
    s = (1.0 + e * e + 2.0 * e * np.cos(Z)) / den  # (cosh Z + cos Z) / (sinh Z + sin Z)
    c_plus = (np.sin(Z) - np.cos(Z) - e) / den  # (1 - s) e^Z / 2
    c_minus = 0.5 * (1.0 + s)
    return s, c_plus, c_minus


def transverse_modes(x, n_modes, params, derivative=0):
    """Beam functions ``f2`` (Eq. 11) or their ``derivative``-th x-derivative at abscissae ``x``.

    Parameters
    ----------
    x : array_like, shape (m,)
        Positions along the beam, ``0 <= x <= L`` (m).
    n_modes : int
        Number of modes, 1..20.
    params : BeamParameters or BeamSections
        Supplies ``L`` and the normalising mass per unit length ``rhoA_ref``.
    derivative : int
        0 for ``f2``, 1 for ``f2'``, 2 for ``f2''``, 3 for ``f2'''``.

    Returns
    -------
    ndarray, shape (m, n_modes)
        Mass-normalised values, units kg^-1/2 m^-derivative.
    """
    _check_request(n_modes, derivative)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    L = float(params.L)
    Z = clamped_free_roots(n_modes)
    s, c_plus, c_minus = _beam_coefficients(Z)
    z = np.multiply.outer(x, Z / L)
    k = derivative
    cos_sign, cos_fun = _COS_DERIVATIVES[k % 4]
    sin_sign, sin_fun = _SIN_DERIVATIVES[k % 4]
    phi = (
        c_plus * np.exp(z - Z)
        + (-1.0) ** k * c_minus * np.exp(-z)
        - cos_sign * cos_fun(z)
        + s * sin_sign * sin_fun(z)
    )
    # int_0^L phi^2 dx = L for the clamped-free eigenfunctions, hence the scale 1/sqrt(rho A L).
    return phi * (Z / L) ** k / np.sqrt(params.rhoA_ref * L)


def axial_modes(x, n_modes, params, derivative=0):
    """Rod functions ``f1`` (Eq. 11) or their ``derivative``-th x-derivative at abscissae ``x``.

    ``f1_i = sqrt(2 / (rho A_ref L)) sin(a_i x)`` with ``a_i = (2i - 1) pi / (2L)`` (unit modal
    mass; ``rho A_ref = params.rhoA_ref``);
    returns an array of shape (m, n_modes), units kg^-1/2 m^-derivative.
    """
    _check_request(n_modes, derivative)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    L = float(params.L)
    a = (2.0 * np.arange(1, n_modes + 1) - 1.0) * np.pi / (2.0 * L)
    sign, fun = _SIN_DERIVATIVES[derivative % 4]
    return sign * fun(np.multiply.outer(x, a)) * a**derivative * np.sqrt(
        2.0 / (params.rhoA_ref * L)
    )
