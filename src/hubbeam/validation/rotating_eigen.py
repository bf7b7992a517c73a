"""Vibrations of the beam at constant hub speed, in the dimensionless form of the literature.

Chordwise (in the plane of rotation). Hold the hub speed at ``theta_dot = Omega``
(``theta_ddot = 0``). The q-rows of the FOAM equations (Eq. 24 with Eqs. 29-33, note 2) become

    M1 q1'' - 2 Omega R   q2' + (K1 - Omega^2 M1) q1            = Omega^2 V1^T
    M2 q2'' + 2 Omega R^T q1' + (K2 - Omega^2 M2 + Omega^2 D) q2 = 0

Every coefficient is constant, so the equations are *linear* in ``(q1, q2)``: the steady state is
the centrifugal stretch ``q1s = Omega^2 (K1 - Omega^2 M1)^-1 V1^T``, ``q2s = 0``, and the deviation
``x = (q1 - q1s, q2)`` obeys exactly (no linearisation error, whatever the amplitude)

    M x'' + G x' + K x = 0,     M = diag(M1, M2),     G = 2 Omega [[0, -R], [R^T, 0]],
                                K = diag(K1 - Omega^2 M1, K2 - Omega^2 M2 + Omega^2 D).

The steady stretch does not enter the chordwise stiffness: FOAM's centrifugal stiffening
``Omega^2 D`` is the tension of the *undeformed* beam. (A geometrically exact beam linearised
about its stretched state would differ at relative order ``(gamma / alpha)^2``, the axial strain
of the steady state; the chordwise benchmark of Hamza-Cherif and Houmat is the small-strain model,
like FOAM.) The matrices and the solver of this gyroscopic quadratic eigenproblem (QEP) are those
of :mod:`hubbeam.model.linearised`.

Flapwise (out of the plane). With ``w = f2 q3`` perpendicular to the plane of rotation the
foreshortening is ``wc = -1/2 int_0^x (v'^2 + w'^2) dxi``. The velocity of a beam point gains
``w' e_z`` only: the rotation ``Omega e_z`` crosses ``e_z`` to zero, so ``w`` has neither a
centrifugal term ``Omega^2 w^2`` (no ``-Omega^2 M2`` softening) nor a Coriolis coupling; the
kinetic-energy term ``Omega^2 int rho A (rA + x) wc dx = -1/2 Omega^2 q3^T D q3`` gives the same
stiffening as in the plane. Hence ``M2 q3'' + (K2 + Omega^2 D) q3 = 0``, uncoupled from ``q1``
at first order. Removing the axial coupling (``R = 0``) from the chordwise problem leaves
``M2 q2'' + (K2 + Omega^2 D - Omega^2 M2) q2 = 0``, whose eigenvalues are the flapwise ones minus
``Omega^2``: ``omega_c^2 = omega_f^2 - gamma^2`` (dimensionless).

Dimensionless form (the sources' own, see :mod:`hubbeam.validation.published`): with ``L = 1``,
``rho A = 1``, ``E I = 1`` and ``E A = alpha^2`` the speed is ``Omega = gamma`` and every circular
frequency is ``omega_bar``; :func:`dimensionless_parameters` builds that beam.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import scipy.optimize
import xarray as xr

from hubbeam.model import linearised
from hubbeam.model.matrices import MODE_NORMALISATION, assemble
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.validation import published

#: direction -> (variant of Eq. 31 in :mod:`hubbeam.model.linearised`, axial coordinates coupled)
_DIRECTION_SYSTEMS = {"flapwise": ("flapwise", False), "chordwise": ("FOAM", True),
                      "chordwise_uncoupled": ("FOAM", False)}
DIRECTIONS = tuple(_DIRECTION_SYSTEMS)


def dimensionless_parameters(alpha: float, delta: float) -> BeamParameters:
    """The beam with ``L = rho A = E I = 1``, slenderness ``alpha`` and hub radius ratio ``delta``.

    ``A = alpha^2``, ``I = 1``, ``E = 1``, ``rho = alpha^-2``, so ``E A = alpha^2`` and
    ``sqrt(rho A L^4 / (E I)) = 1``: a hub speed ``Omega`` is the speed ratio ``gamma`` and a
    circular frequency is the dimensionless ``omega_bar``. ``Jh`` does not enter at constant
    speed and is set to 1.
    """
    if not (np.isfinite(alpha) and alpha > 0.0):
        raise ValueError(f"alpha = {alpha!r}: expected a finite slenderness sqrt(A L^2 / I) > 0")
    if not (np.isfinite(delta) and delta >= 0.0):
        raise ValueError(f"delta = {delta!r}: expected a finite hub radius ratio rA / L >= 0")
    return BeamParameters(L=1.0, rho=alpha**-2, A=alpha**2, E=1.0, I=1.0, Jh=1.0, rA=delta)


def _system(direction: str):
    try:
        return _DIRECTION_SYSTEMS[direction]
    except KeyError:
        raise ValueError(f"direction = {direction!r}: expected one of {', '.join(DIRECTIONS)}") from None


def frequencies(sm, speed: float, direction: str) -> np.ndarray:
    """Circular frequencies (ascending) of the free vibrations at constant ``speed``.

    ``direction`` is ``"flapwise"`` (``K2 + Omega^2 D``), ``"chordwise"`` (q1 and q2 with the
    Coriolis coupling, FOAM's Eqs. 29-31) or ``"chordwise_uncoupled"`` (q2 alone, ``R``
    removed); the matrices are :func:`hubbeam.model.linearised.constant_speed_matrices`, tip-mass
    terms included when ``sm`` has them.

    Without gyroscopic terms this is the symmetric problem ``K x = omega^2 M x``; a negative
    ``omega^2`` (beyond a critical speed) gives NaN. With them, one frequency ``|Im lambda|`` per
    conjugate pair of :func:`hubbeam.model.linearised.quadratic_eigenvalues`; a divergent pair (real
    ``lambda``) gives 0.
    """
    model, axial = _system(direction)
    return linearised.frequencies(sm, model, float(speed), axial)


def first_frequency(gamma: float, alpha: float, delta: float, direction: str, n_modes: int,
                    n_quad: int = 64, mu: float = 0.0) -> float:
    """Dimensionless first frequency ``omega_bar_1`` at speed ratio ``gamma``.

    ``alpha`` slenderness, ``delta`` hub radius ratio, ``mu`` tip-mass ratio ``m_t / (rho A L)``
    (point mass at the tip), ``n_modes`` assumed modes for each of q1 and q2.
    """
    params = dimensionless_parameters(alpha, delta)
    tip = TipMass(mass=mu, position=1.0) if mu else None
    return float(frequencies(assemble(params, tip, n_modes, n_quad), gamma, direction)[0])


def richardson(n_modes, values) -> tuple[float, float]:
    """Extrapolate ``values`` (converging in ``n_modes``, three levels) to infinitely many modes.

    Assumes ``f(n) = f_inf + C n^-p`` and solves for the order ``p`` from the three values, then
    for ``f_inf``. Returns ``(f_inf, p)``; ``(values[-1], nan)`` when the last two values agree to
    1e-12 relative or the differences are not monotone (no algebraic convergence to fit).
    """
    (n1, n2, n3), (f1, f2, f3) = np.asarray(n_modes, float), np.asarray(values, float)
    d12, d23 = f1 - f2, f2 - f3
    if abs(d23) <= 1e-12 * abs(f3) or d12 * d23 <= 0.0 or abs(d12) <= abs(d23):
        return float(f3), float("nan")
    ratio = d12 / d23

    def mismatch(p):
        return (n1**-p - n2**-p) / (n2**-p - n3**-p) - ratio

    try:
        p = scipy.optimize.brentq(mismatch, 1e-3, 50.0, xtol=1e-12)
    except ValueError:
        return float(f3), float("nan")
    return float(f3 - d23 * n3**-p / (n2**-p - n3**-p)), float(p)


def allowed_interval(printed: str, rounding: str, modal_change: float) -> tuple[float, float]:
    """Bounds on (ours - published) that count as agreement.

    The published precision gives the interval of exact values behind the printed digits:
    ``[-u/2, u/2]`` when rounded, ``[0, u)`` when truncated (``u`` one unit in the last printed
    place). Our own error is the modal truncation, estimated by the change of the value between
    the two largest mode counts (the Ritz values converge monotonically, faster than that change
    for the observed algebraic order of about 4, see docs/validation.md); it widens both ends.
    """
    unit = published.printed_unit(printed)
    low, high = {"rounded": (-0.5 * unit, 0.5 * unit), "truncated": (0.0, unit)}[rounding]
    return low - modal_change, high + modal_change


def published_comparison(n_modes=(10, 15, 20), n_quad: int = 64) -> pd.DataFrame:
    """Every published rotating first frequency beside ours, one row per published value.

    Columns: ``source, direction, gamma, alpha, delta, printed, published, rounding``, our
    ``omega_n<k>`` for each mode count, ``modal_change`` (last two counts), ``extrapolated`` and
    ``observed_order`` (:func:`richardson`, with three counts), ``difference`` (largest count minus
    published), the allowed interval ``allowed_low, allowed_high`` and ``agrees``. The flapwise
    frequency does not depend on ``alpha``; it is computed with ``alpha = 70`` where none is given.
    """
    n_modes = tuple(int(n) for n in n_modes)
    if len(n_modes) < 2 or list(n_modes) != sorted(set(n_modes)):
        raise ValueError(f"n_modes = {n_modes!r}: expected at least two increasing mode counts")
    systems = {}
    rows = []
    for entry in published.ROTATING_FIRST_FREQUENCIES:
        alpha = entry.alpha if entry.alpha is not None else 70.0
        ours = []
        for n in n_modes:
            key = (alpha, entry.delta, n)
            if key not in systems:
                systems[key] = assemble(dimensionless_parameters(alpha, entry.delta), None, n,
                                        n_quad)
            ours.append(float(frequencies(systems[key], entry.gamma, entry.direction)[0]))
        modal_change = abs(ours[-1] - ours[-2])
        rounding = published.ROUNDING[entry.source]
        low, high = allowed_interval(entry.printed, rounding, modal_change)
        extrapolated, order = (richardson(n_modes[-3:], ours[-3:]) if len(n_modes) >= 3
                               else (float("nan"), float("nan")))
        difference = ours[-1] - entry.value
        rows.append({
            "source": entry.source, "direction": entry.direction, "gamma": entry.gamma,
            "alpha": entry.alpha, "delta": entry.delta, "printed": entry.printed,
            "published": entry.value, "rounding": rounding,
            **{f"omega_n{n}": value for n, value in zip(n_modes, ours)},
            "modal_change": modal_change, "extrapolated": extrapolated, "observed_order": order,
            "difference": difference, "allowed_low": low, "allowed_high": high,
            "agrees": bool(low <= difference <= high),
        })
    return pd.DataFrame(rows)


def tip_mass_comparison(n_modes=(10, 20), n_quad: int = 64) -> pd.DataFrame:
    """Non-rotating first root ``beta_1 L = omega_bar_1^(1/2)`` with a tip mass vs the table."""
    n_modes = tuple(int(n) for n in n_modes)
    rows = []
    params = dimensionless_parameters(70.0, 0.0)
    for entry in published.TIP_MASS_ROOTS:
        tip = TipMass(mass=entry.mu, position=1.0) if entry.mu else None
        ours = [float(np.sqrt(frequencies(assemble(params, tip, n, n_quad), 0.0, "flapwise")[0]))
                for n in n_modes]
        modal_change = abs(ours[-1] - ours[-2])
        low, high = allowed_interval(entry.printed, "rounded", modal_change)
        difference = ours[-1] - entry.value
        rows.append({"mu": entry.mu, "printed": entry.printed, "published": entry.value,
                     **{f"root_n{n}": value for n, value in zip(n_modes, ours)},
                     "modal_change": modal_change, "difference": difference,
                     "allowed_low": low, "allowed_high": high,
                     "agrees": bool(low <= difference <= high)})
    return pd.DataFrame(rows)


def frequency_curves(gammas, alpha: float, delta: float, n_modes: int,
                     n_quad: int = 64) -> xr.Dataset:
    """``omega_bar_1`` against ``gamma`` in the three directions, for plotting and archiving."""
    gammas = np.asarray(gammas, dtype=float)
    sm = assemble(dimensionless_parameters(alpha, delta), None, n_modes, n_quad)
    values = np.array([[frequencies(sm, g, d)[0] for g in gammas] for d in DIRECTIONS])
    long_names = {
        "flapwise": "first flapwise (out-of-plane) frequency, K2 + gamma^2 D",
        "chordwise": "first chordwise (in-plane) frequency, q1 and q2 with Coriolis coupling",
        "chordwise_uncoupled": "first chordwise frequency without the axial coupling (R = 0)",
    }
    return xr.Dataset(
        {f"omega_{d}": ("gamma", values[i], {"units": "1", "long_name": long_names[d]})
         for i, d in enumerate(DIRECTIONS)},
        coords={"gamma": ("gamma", gammas, {"units": "1", "long_name":
                                            "speed ratio Omega sqrt(rho A L^4 / (E I))"})},
        attrs={"title": "first frequencies of the rotating cantilever (dimensionless)",
               "alpha": float(alpha), "delta": float(delta), "n_modes": int(n_modes),
               "n_quad": int(n_quad), "mode_normalisation": MODE_NORMALISATION,
               "frequency_scale": "omega_bar = omega sqrt(rho A L^4 / (E I))"},
    )
