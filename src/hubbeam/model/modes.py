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

**Functions loaded by a tip body** (``TIP_BODY``, docs/tip-body.md). The clamped-free functions
have zero moment and shear at the tip, which a tip body loads with both, so that with a body the
frequencies converge only as ``N^-1``. The eigenfunctions of the uniform beam clamped at the root
and carrying the body at its end, at rest, have the same form with other roots ``Z_i`` and
coefficients ``s_i``: the clamped root keeps ``phi(0) = phi'(0) = 0``, i.e. with the cos
coefficient ``-1`` (a normalisation) ``c_minus = (1 + s) / 2`` and ``s = 1 - 2 c_plus e^{-Z}``; in
``xi = x / L`` the shape is ``c_plus P + Q`` with ``P = e^{Z (xi - 1)} - e^{-Z} e^{-Z xi} - 2 e^{-Z}
sin(Z xi)`` and ``Q = e^{-Z xi} - cos(Z xi) + sin(Z xi)``, both bounded. The body's two end
conditions (shear against the centre's inertia, moment against both inertias; the mass, inertia
and offset ratios ``mu = m / (rho A L)``, ``j = J / (rho A L^3)``, ``eps = e / L``; ``F^(k)`` the
``k``-th derivative in ``xi`` at ``xi = 1``)

    c_plus r_1[P] + r_1[Q] = 0,    r_1[F] = F^(3) + mu Z^4 (F + eps F^(1)),
    c_plus r_2[P] + r_2[Q] = 0,    r_2[F] = -F^(2) + Z^4 (mu eps (F + eps F^(1)) + j F^(1)),

hold together at the roots of the 2 x 2 determinant ``r_1[P] r_2[Q] - r_2[P] r_1[Q]``
(:func:`loaded_roots`), which then give ``c_plus`` (:func:`loaded_coefficients`). The stable
evaluation above carries over; the functions are scaled to unit modal mass of the bare beam, as
the clamped-free ones, ``int_0^L rho A f^2 dx = 1`` (``int_0^1 phi^2 dxi`` by a Gauss rule that
integrates it to rounding), and are orthogonal in the loaded beam's mass and stiffness, so that
hubbeam's frequencies at rest with the body are the exact ones for any number of modes.
"""

import functools
import math

import numpy as np
import scipy.optimize

from hubbeam.model.limits import MAX_MODES, MIN_MODES

#: the clamped-free beam's eigenfunctions, the paper's (the default)
CLAMPED_FREE = "clamped_free"
#: the eigenfunctions of the clamped beam carrying the case's tip body at rest (module docstring)
TIP_BODY = "tip_body"
#: the admissible transverse functions (``hubbeam.model.matrices.assemble``'s ``functions``)
TRANSVERSE_FUNCTIONS = (CLAMPED_FREE, TIP_BODY)
#: grid of the search for the loaded roots: its step (the closed form's,
#: ``hubbeam.validation.tip_body``) and its start (z = 0 is the trivial solution)
_ROOT_GRID_STEP = math.pi / 256
_ROOT_GRID_START = 1e-2
#: Gauss-Legendre nodes of ``int_0^1 phi^2 dxi``: rounding-exact for the roots of 20 modes (Z < 70)
_NORM_NODES = 256

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


def _end_rows(z, load):
    """``(r_1[P], r_1[Q], r_2[P], r_2[Q])`` of the loaded end (module docstring) at the ``z`` of an
    array, for the ``load`` ``(mu, j, eps)``."""
    mu, j, eps = load
    decay = np.exp(-z)
    P, Q = [], []
    for k in range(4):
        sin_k, cos_k = np.sin(z + k * math.pi / 2.0), np.cos(z + k * math.pi / 2.0)
        sign = (-1.0) ** k
        P.append(z**k * (1.0 - sign * decay * decay - 2.0 * decay * sin_k))
        Q.append(z**k * (sign * decay - cos_k + sin_k))
    z4 = z**4
    rows = []
    for F in (P, Q):
        centre = F[0] + eps * F[1]
        rows.append((F[3] + mu * z4 * centre, -F[2] + z4 * (mu * eps * centre + j * F[1])))
    (r1P, r2P), (r1Q, r2Q) = rows
    return r1P, r1Q, r2P, r2Q


def _loaded_determinant(z, load):
    """The 2 x 2 determinant of the loaded end's conditions, each row divided by its largest entry
    (positive factors: the same roots, a determinant of order one)."""
    r1P, r1Q, r2P, r2Q = _end_rows(z, load)
    scale = np.maximum(np.abs(r1P), np.abs(r1Q)) * np.maximum(np.abs(r2P), np.abs(r2Q))
    return (r1P * r2Q - r2P * r1Q) / scale


def loaded_roots(n_modes, load):
    """The first ``n_modes`` roots ``Z = beta L`` of the clamped beam loaded at its end by a body of
    ``load = (mass_ratio, inertia_ratio, offset_ratio)`` (module docstring): the sign changes of the
    determinant on a grid of step pi/256, refined by Brent's method to ``xtol = 1e-15``. With no
    load these are the clamped-free roots of ``1 + cos z cosh z = 0``."""
    _check_request(n_modes, 0)
    roots = []
    start = _ROOT_GRID_START
    while len(roots) < n_modes:
        z = start + _ROOT_GRID_STEP * np.arange(2049)
        values = _loaded_determinant(z, load)
        for k in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0.0)[:n_modes - len(roots)]:
            roots.append(scipy.optimize.brentq(lambda w: float(_loaded_determinant(np.array(w), load)),
                                               z[k], z[k + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps))
        start = z[-1]
    return np.array(roots)


@functools.lru_cache(maxsize=64)
def loaded_coefficients(n_modes, load):
    """``(Z, s, c_plus, c_minus, norm)`` of the functions loaded by the tip body ``load`` (a tuple
    ``(mass_ratio, inertia_ratio, offset_ratio)``; module docstring): the roots, the coefficients
    of the stable form and ``norm = int_0^1 phi^2 dxi``. ``c_plus`` is taken from the end condition
    in which it weighs more (read-only arrays: the results are cached)."""
    Z = loaded_roots(n_modes, load)
    r1P, r1Q, r2P, r2Q = _end_rows(Z, load)
    first = (np.abs(r1P) * np.maximum(np.abs(r2P), np.abs(r2Q))
             >= np.abs(r2P) * np.maximum(np.abs(r1P), np.abs(r1Q)))
    c_plus = np.where(first, -r1Q / r1P, -r2Q / r2P)
    s = 1.0 - 2.0 * c_plus * np.exp(-Z)
    c_minus = 0.5 * (1.0 + s)
    nodes, weights = np.polynomial.legendre.leggauss(_NORM_NODES)
    z = np.multiply.outer(0.5 * (nodes + 1.0), Z)
    phi = c_plus * np.exp(z - Z) + c_minus * np.exp(-z) - np.cos(z) + s * np.sin(z)
    norm = 0.5 * weights @ phi**2
    for array in (Z, s, c_plus, c_minus, norm):
        array.setflags(write=False)
    return Z, s, c_plus, c_minus, norm


def transverse_modes(x, n_modes, params, derivative=0, load=None):
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
    load : tuple or None
        None for the clamped-free functions; a tip body's ``(mass_ratio, inertia_ratio,
        offset_ratio)`` for the functions it loads (module docstring; a uniform beam with the
        body at its end, which ``hubbeam.model.matrices.assemble`` checks).

    Returns
    -------
    ndarray, shape (m, n_modes)
        Mass-normalised values, units kg^-1/2 m^-derivative.
    """
    _check_request(n_modes, derivative)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    L = float(params.L)
    if load is None:
        Z = clamped_free_roots(n_modes)
        s, c_plus, c_minus = _beam_coefficients(Z)
        mass = params.rhoA_ref * L
    else:
        Z, s, c_plus, c_minus, norm = loaded_coefficients(n_modes, tuple(float(r) for r in load))
        mass = params.rhoA_ref * L * norm
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
    return phi * (Z / L) ** k / np.sqrt(mass)


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
