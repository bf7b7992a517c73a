"""Eigen-analysis of the transverse subsystem at constant hub speed (Table 2, Fig. 9, Section 4.4).

At a constant angular velocity ``Omega`` the transverse equations of TLAM and FOAM (Eqs. 24, 31,
42) read ``M2 q2'' + K22(Omega) q2 = (coupling to q1)`` with the generalised stiffness

    TLAM: K22 = K2 - Omega^2 M2,         FOAM: K22 = K2 - Omega^2 M2 + Omega^2 D,      (31)

where ``M2`` and ``D`` include the tip-mass terms ``m_t f2(l)^T f2(l)`` and ``m_t (rA + l) S(l)``
(Section 4.4, Appendix A5, A8); the formula and the eigensolvers are those of
:mod:`hubbeam.model.linearised`, shared with the published-table validation. We read the paper's
Table 2 as the frequencies of this transverse subsystem alone, the Coriolis coupling
``2 Omega R`` to the axial coordinates and the hub left out (the paper does not say; reproduction
note 13). Under this reading the TLAM row without tip mass is exactly
``sqrt(omega_i^2 - Omega^2)``, and the printed TLAM row follows from the printed natural row by
that formula to all printed digits. :func:`gyroscopic_eigenvalues` adds the axial coordinates and
the Coriolis coupling for comparison. Frequencies are the square roots of the
generalised eigenvalues of ``(K22, M2)``; eigenvalues of ``K22`` itself (Fig. 9) depend on the mode
normalisation, here unit modal mass of the bare beam (note 7), and are in s^-2.

Critical speed: ``K22`` loses positive definiteness at the smallest ``Omega`` for which
``K2 v = Omega^2 B v`` with ``B = M2`` (TLAM) or ``B = M2 - D`` (FOAM)
(:func:`hubbeam.model.linearised.centrifugal_matrix`), i.e. at ``Omega_c =
mu_max^(-1/2)`` with ``mu_max`` the largest eigenvalue of ``B v = mu K2 v`` (``K2`` is positive
definite), when ``mu_max > 0``. This is exact (no root search). For FOAM, ``M2 - D`` is negative
definite whenever ``rA > 0``: with ``w = f2 q2``, ``w(0) = 0`` and Cauchy-Schwarz,
``w(x)^2 = (int_0^x w' dxi)^2 <= x int_0^x w'^2 dxi < (rA + x) int_0^x w'^2 dxi``, integrated
against ``rho A dx`` plus the point mass gives ``q2^T M2 q2 < q2^T D q2``; FOAM has no critical
speed, for any tip mass and position.
"""

import numpy as np
import pandas as pd
import scipy.optimize
import xarray as xr

from hubbeam.core.system_matrices import transverse_mass
from hubbeam.model import linearised
from hubbeam.model import printed as paper
from hubbeam.model.beam import beam_attributes
from hubbeam.model.matrices import MODE_NORMALISATION, assemble, point_mass_terms
from hubbeam.model.models import model as model_traits
from hubbeam.model.parameters import TipMass, UniformBeam
from hubbeam.model.root import RootSpring, checked_spring, joint_second_order

#: the linearisations of the eigen-analysis (the variants of Eq. 31 with the axial coupling: TLAM's
#: and FOAM's, the latter also SFOAM's and CFOAM's, ``hubbeam.model.models``)
LINEARISATIONS = linearised.AXIAL_MODELS


def _check_model(model):
    if model not in LINEARISATIONS:
        raise ValueError(
            f"model = {model!r}: the eigen-analysis is defined for {', '.join(LINEARISATIONS)}"
        )


def K22(sm, model, speed):
    """Generalised stiffness ``K22(Omega)`` of Eq. (31) (with tip mass, Section 4.4).

    ``speed`` (rad s-1) may be an array of shape ``s``; the result has shape ``s + (n, n)``
    (:func:`hubbeam.model.linearised.transverse_stiffness`).
    """
    _check_model(model)
    return linearised.transverse_stiffness(sm.K2, sm.M2, sm.D, model, speed)


def natural_frequencies(sm, root_spring: RootSpring | None = None):
    """Circular natural frequencies (rad s-1) of the non-rotating beam with its hub held:
    ``(K2, M2t)``, ``M2t`` with a tip body's rotary inertia (``transverse_mass``); with a compliant
    root (``root_spring``, ``hubbeam.model.root``) the beam's root angle joins ``q2``, held by the
    spring to the hub (:func:`root_frequencies` at rest, the bending block)."""
    if checked_spring(root_spring) is None:
        return linearised.frequencies_from_squares(linearised.symmetric_eigenvalues(sm.K2, transverse_mass(sm)))
    M, _, _, K, _ = joint_second_order(sm, root_spring, model_traits("TLAM"), 0.0, np.zeros((2,) + sm.K2.shape))
    n = sm.K2.shape[0]
    bending = np.r_[0, 1 + n:1 + 2 * n]  # at rest the axial coordinates and the hub's part
    return linearised.frequencies_from_squares(linearised.symmetric_eigenvalues(K[np.ix_(bending, bending)],
                                                                                M[np.ix_(bending, bending)]))


#: the hub conditions of :func:`root_frequencies`
ROOT_HUBS = ("held", "free")


def root_frequencies(sm, root_spring: RootSpring, model: str = "FOAM", speed: float = 0.0, hub: str = "held"):
    """Circular frequencies (rad s-1, one per conjugate pair, ascending) of ``model``'s undamped
    vibrations about the steady spin at ``speed`` with the compliant root ``root_spring``
    (``hubbeam.model.root.joint_second_order``): the hub ``held`` at the speed (its angle removed,
    the beam's root turning on the spring) or ``free`` (hub and link turn together in a rigid-body
    mode of frequency 0; the hub's inertia ``sm.Jh`` on the other side of the spring). The axial
    coordinates and the Coriolis coupling are kept (``gyroscopic_frequencies`` with the root); a
    divergent direction shows as 0."""
    if checked_spring(root_spring) is None:
        raise ValueError("root_spring = None; allowed: a hubbeam.model.root.RootSpring (the frequencies of a "
                         "rigid root: gyroscopic_frequencies)")
    if hub not in ROOT_HUBS:
        raise ValueError(f"hub = {hub!r}; allowed: one of {', '.join(ROOT_HUBS)}")
    M, G, _, K, _ = joint_second_order(sm, root_spring, model_traits(model), float(speed),
                                       np.zeros((2,) + sm.K2.shape))
    if hub == "held":
        M, G, K = M[:-1, :-1], G[:-1, :-1], K[:-1, :-1]
    return linearised.pair_frequencies(linearised.quadratic_eigenvalues(M, G, K))


def transverse_frequencies(sm, model, speed):
    """Circular frequencies (rad s-1) of the transverse subsystem ``(K22(Omega), M2)``.

    ``speed`` may be an array of shape ``s``; the result has shape ``s + (n,)``, ascending, NaN
    for directions in which ``K22`` is negative (beyond a critical speed).
    """
    _check_model(model)
    return linearised.frequencies(sm, model, speed)


def _mu_max(K2, B):
    """Largest eigenvalue of ``B v = mu K2 v`` for a stack of symmetric ``B`` (s^2)."""
    return linearised.symmetric_eigenvalues(B, np.broadcast_to(K2, B.shape))[..., -1]


def _critical_from_mu(mu_max, search_max):
    with np.errstate(divide="ignore", invalid="ignore"):
        speed = np.where(mu_max > 0.0, 1.0 / np.sqrt(np.abs(mu_max)), np.inf)
    return np.where(speed <= search_max, speed, np.nan)


def _check_search_max(search_max):
    if not (np.isfinite(search_max) and search_max > 0.0):
        raise ValueError(
            f"eigen.critical_speed_search_max = {search_max!r}: expected a finite speed > 0 rad/s"
        )


def critical_speed(model, params, tip, n_modes, search_max, n_quad=64):
    """Critical angular velocity (rad s-1) at which ``K22`` stops being positive definite, for the
    beam ``params`` with ``tip`` (:func:`critical_speed_of` on its matrices)."""
    return critical_speed_of(assemble(params, tip, n_modes, n_quad), model, search_max)


def critical_speed_of(sm, model, search_max, root_spring: RootSpring | None = None):
    """Critical angular velocity (rad s-1) of the matrices ``sm`` with the hub held: the lowest
    speed at which the stiffness of ``model``'s linearisation stops being positive definite; NaN
    when there is none up to ``search_max`` (always for FOAM, see the module docstring).

    Clamped to the hub, exact: ``Omega_c = mu_max^(-1/2)``, ``mu_max`` the largest eigenvalue of
    ``(M2 - c D) v = mu K2 v`` (c = 0 TLAM, 1 FOAM). On a compliant root ``root_spring`` the root's
    angle joins ``q2`` and the spring's stiffness the lag direction: the first zero of the lowest
    eigenvalue of the hub-held stiffness of ``hubbeam.model.root.joint_second_order`` (Brent's
    method, bracketed on a grid of 400 speeds).
    """
    _check_search_max(search_max)
    _check_model(model)
    if checked_spring(root_spring) is None:
        B = linearised.centrifugal_matrix(sm.M2, sm.D, model)
        return float(_critical_from_mu(_mu_max(sm.K2, B), search_max))
    traits, damping = model_traits(model), np.zeros((2,) + sm.K2.shape)

    def lowest(speed):
        K = joint_second_order(sm, root_spring, traits, float(speed), damping)[3][:-1, :-1]
        return np.linalg.eigvalsh(0.5 * (K + K.T))[0]

    return _first_zero(lowest, search_max, 1e-14)


def _first_zero(lowest, search_max: float, tolerance: float) -> float:
    """The lowest speed in ``[0, search_max]`` at which ``lowest(speed)``, the smallest eigenvalue
    of a stiffness, reaches zero: the first sign change on a grid of 400 steps, refined by Brent's
    method to ``tolerance``; 0 if it is not positive at rest, NaN if it stays positive."""
    grid = np.linspace(0.0, search_max, 401)
    values = np.array([lowest(speed) for speed in grid])
    negative = np.flatnonzero(values <= 0.0)
    if negative.size == 0:
        return float("nan")
    k = negative[0]
    return float(grid[0]) if k == 0 else float(scipy.optimize.brentq(lowest, grid[k - 1], grid[k], xtol=tolerance,
                                                                    rtol=tolerance))


def critical_speed_by_root_search(model, params, tip, n_modes, search_max, n_quad=64):
    """Slow cross-check of :func:`critical_speed`: Brent's method on ``lambda_min(K22(Omega))``.

    Brackets the first sign change on a grid of 400 speeds in ``[0, search_max]``; NaN if none.
    """
    sm = assemble(params, tip, n_modes, n_quad)

    def lowest(speed):
        return np.linalg.eigvalsh(K22(sm, model, speed))[0]

    return _first_zero(lowest, search_max, 1e-15)


def tip_mass_frequency_roots(mu, count):
    """Roots ``b = beta L`` of the clamped-free beam with a tip mass (continuum, non-rotating).

    ``1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0`` with ``mu = m_t / (rho A L)``,
    solved in the overflow-free form divided by ``cosh b``; the circular frequencies are
    ``b^2 sqrt(EI / (rho A L^4))``. Used as the exact reference of the TLAM critical speed with a
    tip mass at ``l = L``.
    """
    if not (np.isfinite(mu) and mu >= 0.0):
        raise ValueError(f"mu = {mu!r}: expected a finite mass ratio >= 0")

    def equation(b):
        sech = 1.0 / np.cosh(b) if b < 700.0 else 0.0
        return sech + np.cos(b) + mu * b * (np.cos(b) * np.tanh(b) - np.sin(b))

    # consecutive roots are at least pi/2 apart: a grid step of pi/8 brackets each one
    grid = np.arange(1, 8 * (count + 2)) * np.pi / 8
    values = np.array([equation(b) for b in grid])
    changes = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))[:count]
    return np.array(
        [scipy.optimize.brentq(equation, grid[k], grid[k + 1], xtol=1e-15, rtol=1e-15)
         for k in changes]
    )


# ---------------------------------------------------------------------------------------------
# sweeps over tip mass, tip position and angular velocity, as labelled datasets


def _mass_position_matrices(params, masses, positions, n_modes, n_quad):
    """Bare-beam matrices and ``M2``, ``D`` for every (mass, position), shape (m, p, n, n)."""
    bare = assemble(params, None, n_modes, n_quad)
    tip = point_mass_terms(params, np.asarray(masses, float)[:, None],
                           np.asarray(positions, float)[None, :], n_modes, n_quad)
    return bare, bare.M2 + tip["M2"], bare.D + tip["D"]


def _attributes(params, n_modes, n_quad):
    attrs = {"n_modes": int(n_modes), "n_quad_requested": int(n_quad),
             "mode_normalisation": MODE_NORMALISATION,
             "subsystem": "transverse coordinates q2 only (Coriolis coupling to q1 and the hub "
                          "left out), K22 of Eq. (31) with the tip-mass terms of Section 4.4"}
    attrs |= beam_attributes(params)
    return attrs


def _coords(masses=None, positions=None, speeds=None, n_modes=None):
    coords = {"model": ("model", list(LINEARISATIONS), {"long_name": "model (Section 3)"})}
    if masses is not None:
        coords["tip_mass"] = ("tip_mass", np.asarray(masses, float),
                              {"units": "kg", "long_name": "tip mass m_t"})
    if positions is not None:
        coords["position"] = ("position", np.asarray(positions, float),
                              {"units": "m", "long_name": "tip-mass position l from the clamp"})
    if speeds is not None:
        coords["speed"] = ("speed", np.asarray(speeds, float),
                           {"units": "rad s-1", "long_name": "hub angular velocity Omega"})
    if n_modes is not None:
        coords["mode"] = ("mode", np.arange(1, n_modes + 1),
                          {"units": "1", "long_name": "eigenvalue/frequency index, ascending"})
    return coords


def k22_sweep(params, masses, positions, speeds, n_modes, n_quad=64):
    """Eigenvalues of ``K22`` (s^-2) over model x tip mass x position x speed (Fig. 9).

    Variables ``eigenvalue`` (ascending along ``mode``) and ``dominant_eigenvalue`` (the lowest,
    the paper's 'dominant' one, whose sign change marks the critical speed).
    """
    bare, M2, D = _mass_position_matrices(params, masses, positions, n_modes, n_quad)
    eigenvalues = np.stack([
        np.linalg.eigvalsh(linearised.transverse_stiffness(bare.K2, M2[:, :, None], D[:, :, None],
                                                           model, speeds))
        for model in LINEARISATIONS
    ])
    units = "s-2"
    note = "modes normalised to unit modal mass of the bare beam"
    ds = xr.Dataset(
        {
            "eigenvalue": (("model", "tip_mass", "position", "speed", "mode"), eigenvalues,
                           {"units": units, "long_name": f"eigenvalues of K22 ({note})"}),
            "dominant_eigenvalue": (("model", "tip_mass", "position", "speed"),
                                    eigenvalues[..., 0],
                                    {"units": units,
                                     "long_name": f"lowest eigenvalue of K22 ({note})"}),
        },
        coords=_coords(masses, positions, speeds, n_modes),
        attrs=_attributes(params, n_modes, n_quad) | {"title": "eigenvalues of K22 (Fig. 9)"},
    )
    return ds


def critical_speed_sweep(params, masses, positions, n_modes, search_max, n_quad=64):
    """Critical speeds (rad s-1, NaN where none up to ``search_max``) over mass x position.

    Also stores ``mu_max`` (largest eigenvalue of ``(M2 - c D, K2)``, s^2; a critical speed
    exists iff it is positive) and, for a tip mass at ``l = L``, the TLAM critical speed of the
    continuum beam from :func:`tip_mass_frequency_roots`.
    """
    _check_search_max(search_max)
    bare, M2, D = _mass_position_matrices(params, masses, positions, n_modes, n_quad)
    mu = np.stack([_mu_max(bare.K2, linearised.centrifugal_matrix(M2, D, model))
                   for model in LINEARISATIONS])
    # the continuum frequency equation holds for a uniform beam only: NaN for tabulated sections
    uniform = isinstance(params, UniformBeam)
    continuum = [
        tip_mass_frequency_roots(m / params.beam_mass, 1)[0] ** 2
        * np.sqrt(params.EI / (params.rhoA * params.L**4)) if uniform else np.nan
        for m in np.asarray(masses, float)
    ]
    return xr.Dataset(
        {
            "critical_speed": (("model", "tip_mass", "position"),
                               _critical_from_mu(mu, search_max),
                               {"units": "rad s-1",
                                "long_name": "critical angular velocity (K22 singular); NaN: "
                                             "none up to critical_speed_search_max"}),
            "mu_max": (("model", "tip_mass", "position"), mu,
                       {"units": "s2", "long_name": "largest eigenvalue of (M2 - c D) v = mu K2 v"
                                                    " (c = 0 TLAM, 1 FOAM)"}),
            "continuum_tlam_critical_speed_at_tip": (
                ("tip_mass",), np.array(continuum),
                {"units": "rad s-1",
                 "long_name": "first natural frequency of the continuum cantilever with the tip "
                              "mass at l = L (exact TLAM critical speed; NaN: non-uniform beam)"}),
        },
        coords=_coords(masses, positions),
        attrs=_attributes(params, n_modes, n_quad)
        | {"title": "critical angular velocities (Sections 4.2, 4.4)",
           "critical_speed_search_max": float(search_max)},
    )


def gyroscopic_eigenvalues(sm, model, speed):
    """Eigenvalues ``lambda`` (s-1) of the axial-transverse vibrations at constant hub speed.

    With the hub speed held at ``Omega`` the q-equations of Eq. (24) are linear; about the
    steady stretched state the free vibrations obey

        [M1 0; 0 M2] x'' + 2 Omega [0 -R; R^T 0] x' + [K1 - Omega^2 M1, 0; 0, K22] x = 0,

    ``x = (q1, q2)`` (Eqs. 29-31; TLAM without the D term). ``speed`` of shape ``s`` gives an
    array of shape ``s + (4n,)``, complex (:func:`hubbeam.model.linearised.quadratic_eigenvalues`). A
    stable system has purely imaginary pairs ``+-i omega``; a real pair marks divergence.
    """
    _check_model(model)
    return linearised.eigenvalues(sm, model, speed, axial=True)


def gyroscopic_frequencies(sm, model, speed):
    """Circular frequencies (rad s-1) of :func:`gyroscopic_eigenvalues`, shape ``s + (2n,)``.

    One value per conjugate pair (``|Im lambda|`` sorted, every second one); a divergent
    direction (real pair) shows as frequency 0.
    """
    return linearised.pair_frequencies(gyroscopic_eigenvalues(sm, model, speed))


def campbell(params, masses, speeds, n_modes, n_quad=64):
    """Frequencies (Hz) against hub speed, TLAM and FOAM, tip masses at the beam tip ``l = L``.

    ``frequency`` (and the signed ``omega_squared``) are those of the transverse subsystem
    ``(K22, M2)`` used for Table 2, NaN where ``K22`` is not positive definite (TLAM beyond its
    critical speed). ``frequency_coupled`` and ``growth_rate`` add the axial coordinates and the
    Coriolis coupling (:func:`gyroscopic_eigenvalues`).
    """
    speeds = np.asarray(speeds, dtype=float)
    systems = [assemble(params, TipMass(mass=float(m), position=float(params.L)), n_modes, n_quad)
               for m in masses]
    omega2 = np.stack([[linearised.eigenvalues(sm, model, speeds) for sm in systems]
                       for model in LINEARISATIONS])
    eigenvalues = np.array([[gyroscopic_eigenvalues(sm, model, speeds) for sm in systems]
                            for model in LINEARISATIONS])
    coupled = linearised.pair_frequencies(eigenvalues)
    dims = ("model", "tip_mass", "speed")
    return xr.Dataset(
        {
            "frequency": (dims + ("mode",), linearised.frequencies_from_squares(omega2) / (2 * np.pi),
                          {"units": "Hz", "long_name": "vibration frequency of the transverse "
                                                      "subsystem (NaN: unstable)"}),
            "omega_squared": (dims + ("mode",), omega2,
                              {"units": "s-2", "long_name": "generalised eigenvalue of "
                                                            "(K22, M2), omega^2"}),
            "frequency_coupled": (dims + ("coupled_mode",), coupled / (2 * np.pi),
                                  {"units": "Hz", "long_name": "vibration frequency with axial "
                                   "coordinates and Coriolis coupling (0: divergent direction)"}),
            "growth_rate": (dims, np.max(np.real(eigenvalues), axis=-1),
                            {"units": "s-1", "long_name": "largest real part of the coupled "
                                                          "eigenvalues (> 0: unstable)"}),
        },
        coords=_coords(masses, None, speeds, n_modes)
        | {"coupled_mode": ("coupled_mode", np.arange(1, 2 * n_modes + 1),
                            {"units": "1", "long_name": "coupled frequency index, ascending"})},
        attrs=_attributes(params, n_modes, n_quad)
        | {"title": "Campbell diagram, TLAM and FOAM", "tip_position_m": float(params.L)},
    )


def table2(params, speed, n_modes, n_quad=64):
    """Table 2 (no tip mass): natural, TLAM and FOAM frequencies (Hz) at ``speed``, computed
    and as printed in the paper, one row per mode (the paper prints five)."""
    sm = assemble(params, None, n_modes, n_quad)
    hz = 1.0 / (2 * np.pi)
    table = pd.DataFrame({
        "mode": np.arange(1, n_modes + 1),
        "natural": natural_frequencies(sm) * hz,
        "TLAM": transverse_frequencies(sm, "TLAM", speed) * hz,
        "FOAM": transverse_frequencies(sm, "FOAM", speed) * hz,
    })
    for row, values in paper.TABLE2.items():
        printed = np.full(n_modes, np.nan)
        k = min(n_modes, len(values))
        printed[:k] = values[:k]
        table[f"paper_{row}"] = printed
    return table


def critical_speed_table(params, masses, n_modes, search_max, n_quad=64):
    """Critical speeds (rad s-1) of TLAM and FOAM for each tip mass at the beam tip ``l = L``;
    columns ``model, tip_mass_kg, position_m, critical_speed_rad_s`` (NaN where none)."""
    rows = []
    for model in LINEARISATIONS:
        for mass in masses:
            tip = TipMass(mass=float(mass), position=float(params.L))
            rows.append({"model": model, "tip_mass_kg": float(mass), "position_m": tip.position,
                         "critical_speed_rad_s": critical_speed(model, params, tip, n_modes,
                                                                search_max, n_quad)})
    return pd.DataFrame(rows)
