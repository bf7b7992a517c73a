"""The tip body (``TipMass`` with rotary inertia and an offset centre, docs/tip-body.md) against
closed forms, an independent finite-element model, conservation laws and published numbers.

* the closed-form frequency equation of the clamped beam with the body (4x4 determinant,
  ``hubbeam.validation.tip_body``): its limits (clamped-free, tip mass), its roots to 1e-12, and
  the finite-element model converging to it at the rate of cubic elements;
* the De Luca and Siciliano (1991) link: the closed form against its published 2.18 and 15.91 Hz,
  the point mass's second frequency near 23 Hz;
* hubbeam's eigenvalues at rest, hub held: equal to the finite-element model's in the same trial
  functions (every body term assembled twice, independently), and converging to the closed form
  as modes are added, at the rate the clamped-free functions allow (shown below);
* at speed: FOAM's linearisation against the finite-element model, in the same trial functions
  and converging to the full model;
* the kinematics of the offset centre against the geometry of the deformed beam, CFOAM's exact
  kinetic energy of the body against the body's own, its rotary inertia joining the hub's;
* energy and angular momentum of a free, undamped hub-beam with the body conserved (TLAM, FOAM,
  CFOAM), the work-energy balance under a torque, the body's centre among the outputs;
* bad input named.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import eigh
from test_eom import exact_kinetic_energy

from hubbeam.core import eom
from hubbeam.model import eigen
from hubbeam.model.matrices import S_matrix, assemble
from hubbeam.model.models import MODELS
from hubbeam.model.modes import axial_modes, clamped_free_roots, transverse_modes
from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass
from hubbeam.simulation.simulate import simulate
from hubbeam.validation import fe_beam
from hubbeam.validation.tip_body import (
    DE_LUCA_SICILIANO,
    body_frequencies,
    body_frequency_roots,
    frequency_determinant,
    ritz_convergence,
)

HZ = 1.0 / (2.0 * math.pi)
#: the De Luca and Siciliano link, clamped at the hub (no hub radius: the hub held)
LINK = BeamProducts(L=DE_LUCA_SICILIANO["L"], rhoA=DE_LUCA_SICILIANO["rhoA"], EI=DE_LUCA_SICILIANO["EI"],
                    EA=1.0e4, Jh=0.1, rA=0.0)
PAYLOAD = TipMass(DE_LUCA_SICILIANO["mass"], LINK.L, DE_LUCA_SICILIANO["inertia"])
#: the payload with its centre 3 cm beyond the tip
OFFSET_PAYLOAD = TipMass(PAYLOAD.mass, LINK.L, PAYLOAD.inertia, 0.03)
#: a body on the paper's beam (Table 1): half a kilogram, 2 kg m2, centre 0.3 m beyond the tip
BODY = TipMass(0.5, 8.0, 2.0, 0.3)


@pytest.fixture(scope="module")
def paper_beam(_study_config):
    return BeamParameters.from_config(_study_config)


# --- the closed form --------------------------------------------------------------------------


def test_the_frequency_equation_has_the_known_limits():
    """Without a body the roots are those of ``1 + cos z cosh z = 0`` (``modes.clamped_free_roots``,
    Newton's method on another form), with a point mass those of the tip-mass equation
    (``eigen.tip_mass_frequency_roots``, Brent's method on a third form): both to 1e-12."""
    np.testing.assert_allclose(body_frequency_roots(0.0, 0.0, 0.0, 8), clamped_free_roots(8), rtol=1e-12)
    for mu in (0.1, 1.0, 20.0):
        np.testing.assert_allclose(body_frequency_roots(mu, 0.0, 0.0, 6),
                                   eigen.tip_mass_frequency_roots(mu, 6), rtol=1e-12)


@pytest.mark.parametrize("ratios", [(1.0, 0.02, 0.0), (1.0, 0.02, 0.06), (5.0, 0.3, -0.2)])
def test_the_roots_are_solved_to_1e_12(ratios):
    """The determinant changes sign across ``z (1 -+ 1e-12)`` at every root: each is within
    1e-12 relative of a true root."""
    for z in body_frequency_roots(*ratios, 6):
        below = frequency_determinant(z * (1 - 1e-12), *ratios)
        above = frequency_determinant(z * (1 + 1e-12), *ratios)
        assert below * above < 0.0


@pytest.mark.parametrize("tip", [PAYLOAD, OFFSET_PAYLOAD], ids=["payload", "offset_payload"])
def test_finite_elements_converge_to_the_closed_form(tip):
    """Cubic Hermite elements (``fe_beam``, its own assembly of the body's mass, rotary inertia
    and offset) approach the closed form at their ``h^4`` rate: each doubling of the elements
    divides the error of the first four frequencies by about 16 (at least 12: the rate with
    its next term), down to 1e-8 at 80 elements."""
    exact = body_frequencies(LINK, tip, 4)
    errors = np.array([fe_beam.frequencies(LINK, [0.0], "inplane", tip, n, 4)[0] / exact - 1
                       for n in (10, 20, 40)])
    assert np.all(errors > 0.0)  # elements of a conforming model are stiffer than the beam
    assert np.all(errors[:-1] / errors[1:] >= 12.0)
    fine = fe_beam.frequencies(LINK, [0.0], "inplane", tip, 80, 4)[0]
    np.testing.assert_allclose(fine, exact, rtol=1e-7)
    np.testing.assert_allclose(fine[:2], exact[:2], rtol=1e-8)


def test_de_luca_siciliano_link_against_its_published_frequencies():
    """The closed form rounds to the published 2.18 and 15.91 Hz; as a point mass (no rotary
    inertia) the second frequency is 23.1 Hz."""
    payload = body_frequencies(LINK, PAYLOAD, 2) * HZ
    np.testing.assert_array_equal(np.round(payload, 2), DE_LUCA_SICILIANO["frequencies_hz"])
    point = body_frequencies(LINK, TipMass(PAYLOAD.mass, LINK.L), 2) * HZ
    assert round(point[1]) == 23


# --- hubbeam's eigenvalues --------------------------------------------------------------------


#: elements of the projected model (below): the interpolation error of the 10th function,
#: ``(beta_10 h)^4 / 720``, is 1e-7 and falls with finer elements, while the rounding of the
#: projection, ``eps`` times the element stiffness ``EI / h^3`` summed over the elements against
#: ``K_11``, grows as ``n^4`` (measured on the first frequency: 2e-8 at 200 elements, 1e-7 at 400,
#: 6e-7 at 300 with a hub radius); measured at most 3e-8 on the first four frequencies here
PROJECTED_ELEMENTS = 200


def projected_fe(params, tip, n_modes, speed):
    """The finite-element model's mass and in-plane stiffness at ``speed`` restricted to
    hubbeam's transverse functions: each ``f2_i`` enters as its nodal values and slopes (its
    cubic Hermite interpolant), so ``Phi^T M Phi`` and ``Phi^T K Phi`` are the Ritz matrices of
    the same functions, assembled by the elements. They differ from hubbeam's by the interpolation
    error, ``O(h^4)`` (the interpolant is the best fit in the bending energy), and rounding."""
    n_elements = PROJECTED_ELEMENTS
    nodes = fe_beam.mesh(params, n_elements, tip.position)[1:]  # the root's DOFs are removed
    Phi = np.empty((2 * nodes.size, n_modes))
    Phi[0::2] = transverse_modes(nodes, n_modes, params)
    Phi[1::2] = transverse_modes(nodes, n_modes, params, derivative=1)
    fe = fe_beam.matrices(params, tip, n_elements)
    stiffness = fe.K + speed**2 * (fe.G - fe.M)
    return Phi.T @ (fe.M + fe.R) @ Phi, Phi.T @ stiffness @ Phi


@pytest.mark.parametrize("tip", [PAYLOAD, OFFSET_PAYLOAD], ids=["payload", "offset_payload"])
def test_hubbeam_at_rest_equals_the_finite_elements_in_the_same_functions(tip):
    """hubbeam's eigenvalues at rest with the hub held (``eigen.natural_frequencies``: ``K2``
    against ``M2`` with the body's mass at its centre and its rotary inertia) equal those of the
    element assembly in the same 10 functions: the first four to 1e-7
    (:data:`PROJECTED_ELEMENTS`)."""
    sm = assemble(LINK, tip, 10)
    M, K = projected_fe(LINK, tip, 10, 0.0)
    np.testing.assert_allclose(eigen.natural_frequencies(sm)[:4], np.sqrt(eigh(K, M, eigvals_only=True))[:4],
                               rtol=1e-7)


def ritz_errors(tip, modes):
    """Relative errors of hubbeam's first three frequencies at rest, hub held, against the
    closed form, for each number of modes."""
    exact, ritz = ritz_convergence(LINK, tip, modes)
    return ritz / exact - 1


def test_a_point_mass_converges_as_the_cube_of_the_modes():
    """The clamped-free functions have zero shear at the tip; a point mass needs shear there:
    the modal series of its modes converges as ``1 / beta_k^4``, the frequencies as ``N^-3``
    (measured order 2.99 from 10 to 20 modes for each of the first three; asserted within 0.1
    of 3), and 20 modes reach 2e-6 on the first frequency, 2e-5 on the second."""
    errors = ritz_errors(TipMass(PAYLOAD.mass, LINK.L), (5, 10, 20))
    assert np.all(errors > 0.0) and np.all(np.diff(errors, axis=0) < 0.0)  # Rayleigh-Ritz
    order = np.log2(errors[1] / errors[2])
    np.testing.assert_allclose(order, 3.0, atol=0.1)
    assert errors[2, 0] < 2e-6 and errors[2, 1] < 2.5e-5


@pytest.mark.parametrize("tip", [PAYLOAD, TipMass(PAYLOAD.mass, LINK.L, 0.0, 0.03)],
                         ids=["rotary_inertia", "offset"])
def test_a_body_converges_as_the_modes(tip):
    """A body's rotary inertia or offset centre loads the tip with a moment, which bends the
    beam there (``W''(L) != 0``), while every clamped-free function has zero curvature at the tip:
    the modal series converges as ``1 / beta_k^3``, the frequencies as ``N^-1`` only, behind the
    ``N^-3`` of the end shear. Asserted: Rayleigh-Ritz upper bounds that fall with every mode
    added, at an observed order of at least 0.9 that falls from 5-10 modes to 10-20 modes
    (towards 1); with the rotary inertia the second and third frequencies are there (measured
    1.02 and 1.05 from 10 to 20 modes, asserted within 0.1 of 1); with the offset alone the end
    moment is small and the order still 1.33. Measured for the De Luca and Siciliano payload:
    the second frequency 6.3 % high with 5 modes, 3.1 % with 10, 1.5 % with 20; 1e-6 would take
    about 3e5 modes. The model's terms themselves agree to 1e-7 with an independent assembly in
    the same functions (the test above)."""
    errors = ritz_errors(tip, (5, 10, 15, 20))
    assert np.all(errors > 0.0) and np.all(np.diff(errors, axis=0) < 0.0)
    early, late = np.log2(errors[0] / errors[1]), np.log2(errors[1] / errors[3])
    assert np.all(late >= 0.9) and np.all(late < early)
    if tip.inertia:
        np.testing.assert_allclose(late[1:], 1.0, atol=0.1)


SPEEDS = (0.0, 10.0, 25.0, 50.0)  # rad s-1; the link's first frequency is 13.7 rad s-1


@pytest.fixture(scope="module")
def spinning_link():
    """The link on a hub of radius 5 cm with the offset payload."""
    return BeamProducts(L=LINK.L, rhoA=LINK.rhoA, EI=LINK.EI, EA=LINK.EA, Jh=LINK.Jh, rA=0.05)


def test_foam_linearisation_at_speed_equals_the_finite_elements_in_the_same_functions(spinning_link):
    """FOAM's transverse linearisation (``K2 + Omega^2 (D - M2)`` against ``M2`` with the body's
    rotary inertia; the offset in ``D`` and ``M2``) equals the element assembly in the same 10
    functions at every speed, the first four frequencies to 1e-7 as at rest: the body's
    centrifugal tension, the pull on its offset centre and the softening of its mass."""
    sm = assemble(spinning_link, OFFSET_PAYLOAD, 10)
    ritz = eigen.transverse_frequencies(sm, "FOAM", np.array(SPEEDS))
    for speed, frequencies in zip(SPEEDS, ritz):
        M, K = projected_fe(spinning_link, OFFSET_PAYLOAD, 10, speed)
        np.testing.assert_allclose(frequencies[:4], np.sqrt(eigh(K, M, eigvals_only=True))[:4], rtol=1e-7)


def test_foam_linearisation_at_speed_converges_to_the_finite_elements(spinning_link):
    """Against the full element model (160 elements, 1e-9 from the continuum at rest) FOAM's
    first three frequencies are upper bounds (Rayleigh-Ritz: ``K2 + Omega^2 (D - M2)`` is positive
    definite) that approach it with every mode added, at every speed, as at rest at an order of
    at least 0.9 from 10 to 20 modes (measured 0.95 to 1.25, 1.9 for the first frequency at 50
    rad s-1). With 20 modes: 2e-4 to 3e-5 on the first frequency, 1.3 % (at rest) to 2.5 % (at
    50 rad s-1) on the second."""
    fe = fe_beam.frequencies(spinning_link, SPEEDS, "inplane", OFFSET_PAYLOAD, 160, 3)
    gaps = np.array([eigen.transverse_frequencies(assemble(spinning_link, OFFSET_PAYLOAD, n), "FOAM",
                                                  np.array(SPEEDS))[:, :3] / fe - 1 for n in (5, 10, 20)])
    assert np.all(gaps > 0.0) and np.all(np.diff(gaps, axis=0) < 0.0)
    assert np.all(np.log2(gaps[1] / gaps[2]) >= 0.9)


# --- kinematics and energy ----------------------------------------------------------------------


def test_the_centre_is_the_last_point_of_the_cloud_to_the_models_order(paper_beam):
    """The centre of a body ``e`` beyond the attachment along the deformed beam's tangent: with
    ``v`` the transverse deflection of an inextensible beam at arc length ``x``, ``v' = sin(phi)``,
    it lies ``(e cos(phi), e sin(phi)) = (e sqrt(1 - v'^2), e v')`` from the attachment. The cloud's
    last point puts it at ``(e - q2^T (S_c - S(l)) q2 / 2, (F2_c - f2(l)) q2)``: equal across,
    and along to ``e v'^4 / 8 (1 + O(v'^2))``, the order the models drop (asserted: the error over
    ``e v'^4 / 8`` within ``v'^2`` of 1, ``v'`` from 0.29 down to 0.07)."""
    n = 5
    sm = assemble(paper_beam, BODY, n)
    l, e = BODY.position, BODY.offset
    f2, slope = transverse_modes(l, n, paper_beam)[0], transverse_modes(l, n, paper_beam, derivative=1)[0]
    S = S_matrix(paper_beam, l, n)[0]
    assert sm.x[-1] == pytest.approx(l + e, rel=1e-15)
    q = np.array([0.4, -0.2, 0.1, 0.05, -0.02])
    for amplitude in (1.0, 0.5, 0.25):
        q2 = amplitude * q
        tilt = slope @ q2  # v'(l) = sin(phi)
        np.testing.assert_allclose((sm.F2[-1] - f2) @ q2, e * tilt, rtol=1e-13)
        along = e - 0.5 * q2 @ (sm.S[-1] - S) @ q2 - e * math.sqrt(1.0 - tilt**2)
        assert along / (e * tilt**4 / 8) == pytest.approx(1.0, abs=tilt**2)


def test_cfoam_kinetic_energy_is_the_beams_and_the_bodys(paper_beam):
    """CFOAM's kinetic energy (``eom.energy`` less the strain energy) is the beam's and the
    hub's (the cloud without its last point) plus the body's, ``m |r_c'|^2 / 2 + Jt (theta' +
    v'(l)')^2 / 2``, its centre ``r_c`` built here from the attachment's position and the tangent:
    ``(rA + l + u(l) - q2^T S(l) q2 / 2 + e (1 - v'(l)^2 / 2), v(l) + e v'(l))`` in the rotating
    frame, differentiated along the motion (central differences, exact for these quadratics)."""
    n = 4
    sm = assemble(paper_beam, BODY, n)
    l, e = BODY.position, BODY.offset
    f1, f2 = axial_modes(l, n, paper_beam)[0], transverse_modes(l, n, paper_beam)[0]
    slope = transverse_modes(l, n, paper_beam, derivative=1)[0]
    S = S_matrix(paper_beam, l, n)[0]
    rng = np.random.default_rng(3)
    y = np.concatenate([[0.3], 0.01 * rng.normal(size=n), 0.3 * rng.normal(size=n)])
    v = np.concatenate([[1.7], 0.1 * rng.normal(size=n), 0.5 * rng.normal(size=n)])

    def centre(yy):
        q1, q2 = yy[1:1 + n], yy[1 + n:]
        tilt = slope @ q2
        return np.array([sm.rA + l + f1 @ q1 - 0.5 * q2 @ S @ q2 + e * (1 - 0.5 * tilt**2), f2 @ q2 + e * tilt])

    X, Y = centre(y)
    Xd, Yd = (centre(y + 1e-3 * v) - centre(y - 1e-3 * v)) / 2e-3
    thd = v[0]
    body = 0.5 * BODY.mass * ((Xd - thd * Y) ** 2 + (Yd + thd * X) ** 2)
    body += 0.5 * BODY.inertia * (thd + slope @ v[1 + n:]) ** 2
    w = sm.w.copy()
    w[-1] = 0.0
    beam = exact_kinetic_energy(sm._replace(w=w, Jt=0.0), y, v)
    strain = eom.strain_energy(y, sm.K1, sm.K2)
    kinetic = eom.energy(MODELS["CFOAM"].traits, y, v, sm) - strain
    assert kinetic == pytest.approx(beam + body, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_the_rotary_inertia_joins_the_hub_inertia_at_rest(paper_beam, model):
    """Spinning rigidly (``q = 0``) the hub-beam has the angular momentum of a rigid body about
    the hub axis: ``Jh + rhoA ((rA + L)^3 - rA^3) / 3 + m (rA + L + e)^2 + Jt`` (parallel axes)
    times the speed."""
    sm = assemble(paper_beam, BODY, 3)
    y = np.zeros(7)
    v = np.zeros(7)
    v[0] = 2.0
    rA, L = paper_beam.rA, paper_beam.L
    rigid = (paper_beam.Jh + paper_beam.rhoA * ((rA + L) ** 3 - rA**3) / 3
             + BODY.mass * (rA + L + BODY.offset) ** 2 + BODY.inertia)
    p = eom.angular_momentum(MODELS[model].traits, y, v, sm)
    assert p == pytest.approx(rigid * 2.0, rel=1e-13)


# --- simulations -------------------------------------------------------------------------------


def body_case(model, maneuver, t_end, modes=3):
    return {"name": f"body_{model}", "model": model, "modes": modes, "t_end": t_end, "maneuver": maneuver,
            "tip_mass": {"mass": BODY.mass, "position": BODY.position}}


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
def test_energy_and_angular_momentum_of_the_free_hub_beam_are_conserved(_study_config, paper_beam, model):
    """A torque pulse (Eq. 44) sets the hub-beam with the body spinning and vibrating (0.25 m at
    the tip); once it has ended the hub is free and undamped: energy and angular momentum stay
    constant to the integrator's tolerance (``rtol`` times their size, as for the point mass;
    measured 1e-12), and the rest-to-rest pulse leaves no net angular momentum."""
    rtol = 1e-9
    numerics = dict(_study_config["numerics"], rtol=rtol, atol=1e-2 * rtol)
    sm = assemble(paper_beam, BODY, 3, numerics["quadrature_points"])
    maneuver = {"kind": "torque", "tau_max": 10.0, "tf": 5.0}
    ds = simulate(body_case(model, maneuver, 12.0), paper_beam, numerics, sm)
    assert ds.attrs["diverged"] == 0
    after = ds.time >= 5.0
    energy = ds.energy[after].values
    momentum = ds.angular_momentum[after].values
    assert float(abs(ds.tip_transverse).max()) > 1e-3  # the body did swing the beam
    assert np.ptp(energy) <= rtol * np.max(abs(energy))
    assert np.ptp(momentum) <= rtol * float(abs(ds.angular_momentum).max())
    assert abs(momentum[0]) <= rtol * float(abs(ds.angular_momentum).max())


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
def test_energy_change_is_the_work_of_the_torque(_study_config, paper_beam, model):
    """``energy(t) - energy(0) = work(t)`` along a torque table: Simpson's rule on the 0.005 s
    output grid integrates the hub's power to ``O(h^4)`` and the run is accurate to its ``rtol``
    (1e-9): measured 8e-10 of the largest work for each model, bound 1e-8."""
    numerics = dict(_study_config["numerics"], output_step=0.005)
    sm = assemble(paper_beam, BODY, 3, numerics["quadrature_points"])
    maneuver = {"kind": "torque_table", "time": [0.0, 1.0, 2.0, 3.0], "torque": [0.0, 60.0, -30.0, 0.0]}
    ds = simulate(body_case(model, maneuver, 4.0), paper_beam, numerics, sm)
    np.testing.assert_allclose(ds.energy.values - ds.energy.values[0], ds.work.values, rtol=0,
                               atol=1e-8 * np.abs(ds.work.values).max())


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_the_bodys_centre_is_among_the_outputs(_study_config, paper_beam, model):
    """``body_transverse`` and ``body_axial`` are the centre's displacement from the run's own
    coordinates, ``(f2(l) + e f2'(l)) q2`` and ``f1(l) q1 - q2^T (S(l) + e f2'(l)^T f2'(l)) q2 / 2``
    (evaluated here from the mode functions); the beam tip's outputs stay the beam tip's."""
    n = 3
    numerics = dict(_study_config["numerics"], output_step=0.05)
    sm = assemble(paper_beam, BODY, n, numerics["quadrature_points"])
    ds = simulate(body_case(model, {"kind": "prescribed", "wf": 1.0, "tf": 4.0}, 5.0, n), paper_beam,
                  numerics, sm)
    l, e = BODY.position, BODY.offset
    slope = transverse_modes(l, n, paper_beam, derivative=1)[0]
    centre = transverse_modes(l, n, paper_beam)[0] + e * slope
    S = S_matrix(paper_beam, l, n)[0] + e * np.outer(slope, slope)
    q1, q2 = ds.q1.values, ds.q2.values
    scale = float(abs(ds.body_transverse).max())
    np.testing.assert_allclose(ds.body_transverse.values, q2 @ centre, rtol=0, atol=1e-12 * scale)
    axial = q1 @ axial_modes(l, n, paper_beam)[0] - 0.5 * np.einsum("ti,ij,tj->t", q2, S, q2)
    np.testing.assert_allclose(ds.body_axial.values, axial, rtol=0, atol=1e-12 * float(abs(axial).max()))
    np.testing.assert_allclose(ds.tip_transverse.values, q2 @ sm.f2L, rtol=0, atol=1e-12 * scale)
    assert scale > 1.01 * float(abs(ds.tip_transverse).max())  # the offset adds e v'(L)


def test_exported_linear_models_record_the_body(paper_beam, tmp_path):
    """The netCDF and MATLAB files of the linear models name the body they were built with."""
    from scipy.io import loadmat

    from hubbeam.linear.export import to_dataset, write_mat
    from hubbeam.model.plant import Plant

    ds = to_dataset(Plant(beam=paper_beam, modes=3, quadrature_points=64, tip=BODY), "FOAM", [0.0, 1.0])
    mat = loadmat(write_mat(ds, tmp_path / "body.mat"))
    for attrs in (ds.attrs, {key: float(np.squeeze(mat[key])) for key in ("tip_inertia_kg_m2", "tip_offset_m")}):
        assert attrs["tip_inertia_kg_m2"] == BODY.inertia and attrs["tip_offset_m"] == BODY.offset


# --- bad input ---------------------------------------------------------------------------------


@pytest.mark.parametrize("tip, message", [
    (TipMass(0.1, 8.0, -1.0), "tip_mass.inertia = -1.0: expected a finite rotary inertia >= 0"),
    (TipMass(0.1, 8.0, math.nan), "tip_mass.inertia = nan"),
    (TipMass(0.1, 2.0, 0.0, -2.5), r"tip_mass.offset = -2.5: expected a finite offset \(m\) with "
                                   r"position \+ offset >= 0 \(position = 2.0 m\)"),
    (TipMass(0.1, 8.0, 0.0, math.inf), "tip_mass.offset = inf"),
    (TipMass(-0.1, 8.0, 1.0, 0.1), "tip_mass.mass = -0.1"),
    (TipMass(0.1, 8.5, 1.0, 0.1), "tip_mass.position = 8.5"),
])
def test_a_bad_body_is_named(paper_beam, tip, message):
    for build in (lambda: assemble(paper_beam, tip, 3), lambda: fe_beam.matrices(paper_beam, tip, 10)):
        with pytest.raises(ValueError, match=message):
            build()


def test_the_closed_form_and_the_elements_refuse_what_they_do_not_model(paper_beam):
    with pytest.raises(ValueError, match="tip_mass.position = 4.0: expected the beam's end"):
        body_frequencies(paper_beam, TipMass(0.1, 4.0, 0.1), 2)
    with pytest.raises(ValueError, match="beam = .*: expected a uniform beam"):
        body_frequencies(None, BODY, 2)
    with pytest.raises(ValueError, match="tip_mass.inertia = 2.0 with direction = 'flapwise'"):
        fe_beam.frequencies(paper_beam, [0.0], "flapwise", BODY, 10, 2)


def test_a_point_mass_is_the_body_without_inertia_and_offset():
    """The defaults: ``TipMass(m, l)`` is ``TipMass(m, l, 0, 0)``, a point mass."""
    assert TipMass(0.5, 8.0) == TipMass(0.5, 8.0, 0.0, 0.0)
    assert TipMass(0.5, 8.0).is_point and not BODY.is_point
