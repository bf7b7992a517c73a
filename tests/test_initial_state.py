"""Runs that start at an operating point (``case["initial"]``, ``hubbeam.simulation.simulate.initial_state``).

* A free hub in steady spin under zero torque (a torque table of zeros) stays there, for every
  model: ``theta_dot`` constant, ``q2 = 0``, ``q1`` at its centrifugal stretch (Eqs. 29-30), all
  to the integrator's tolerance.
* A small deviation along a mode of the constant-speed linearisation (Eqs. 29-31) oscillates at
  the frequency :mod:`hubbeam.model.linearised` gives, for every model, when the hub is heavy enough for
  the free hub to act as the held hub of the linearisation.
* A prescribed hub starts at its maneuver's speed; the initial state is recorded and reproduced;
  bad initial states are rejected naming the key.
"""

import dataclasses

import numpy as np
import pytest

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import simulation_settings
from hubbeam.model import linearised
from hubbeam.model.models import MODELS
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.reader import simulation_inputs
from hubbeam.simulation.simulate import case_matrices, simulate

SPEED = 2.0  # rad s-1, below TLAM's critical speed (2.91 rad/s without tip mass)


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), dict(_study_config["numerics"])


def matrices(case, params, numerics):
    """The system matrices of the case mapping ``case``."""
    case, numerics = simulation_settings(case, numerics, params.L)
    return case_matrices(case, params, numerics)


def spin_case(model, initial, t_end=10.0, modes=2, maneuver=None):
    return {"name": f"spin_{model}", "model": model, "t_end": t_end, "modes": modes,
            "maneuver": maneuver or {"kind": "torque_table", "time": [0.0, 1.0], "torque": [0.0, 0.0]},
            "tip_mass": {"mass": 0.0, "position": 8.0}, "initial": initial}


@pytest.mark.parametrize("model", MODELS)
def test_a_free_hub_in_steady_spin_stays_there(setup, model):
    params, numerics = setup
    case = spin_case(model, {"hub_speed": SPEED})
    ds = simulate(case, params, numerics)
    sm = matrices(case, params, numerics)
    rtol, atol = numerics["rtol"], numerics["atol"]
    q1s = linearised.axial_stretch(sm, SPEED) if MODELS[model].keeps_axial else np.zeros(2)
    assert ds.attrs["integrator_status"] == "success"
    # every accepted step keeps its local error below atol + rtol |x| (weighted RMS <= 1); at the
    # equilibrium the right-hand side is rounding error, so the state may not move by more
    np.testing.assert_allclose(ds["theta_dot"], SPEED, rtol=rtol, atol=atol)
    np.testing.assert_allclose(ds["theta"], SPEED * ds["time"], rtol=rtol, atol=atol)
    np.testing.assert_allclose(ds["q2"], 0.0, atol=atol)
    np.testing.assert_allclose(ds["q1"], np.broadcast_to(q1s, ds["q1"].shape), rtol=rtol, atol=atol)
    assert ds.attrs["initial"] == '{"hub_speed": 2.0}'


def _linear_mode(sm, variant, axial):
    """Initial deviation and rate ``(x0, x0')`` of the slowest mode of ``M x'' + G x' + K x = 0``
    (Eqs. 29-31), scaled to a unit tip deflection, and its circular frequency, from numpy's
    eigen-solver on ``M^-1`` (a route of its own beside
    :func:`hubbeam.model.linearised.quadratic_eigenvalues`)."""
    M, G, K = linearised.constant_speed_matrices(sm, variant, SPEED, axial)
    N = M.shape[0]
    A = np.block([[np.zeros((N, N)), np.eye(N)], [-np.linalg.solve(M, K), -np.linalg.solve(M, G)]])
    values, vectors = np.linalg.eig(A)
    k = np.argmin(np.where(values.imag > 0, values.imag, np.inf))
    tip = np.concatenate([np.zeros(N - sm.f2L.size), sm.f2L])
    X = vectors[:N, k] / (tip @ vectors[:N, k])
    return X.real, (values[k] * X).real, values[k].imag


@pytest.mark.parametrize("model", MODELS)
def test_a_small_deviation_oscillates_at_the_linearised_frequency(setup, model):
    """The held hub of the linearisation is approached by a free hub of inertia ``Jh``: the hub row
    couples to ``q2`` through ``V2`` (Eq. 27), which shifts ``omega^2`` by a relative amount of
    order ``|V2|^2 / Jh`` (mass-normalised modes). The tolerance is ten times that, plus the
    integrator's relative tolerance for the phase; the deflection is 1e-5 of the length, so the
    neglected nonlinear terms are of relative order 1e-10. The zero crossings of the tip
    deflection are interpolated linearly between output times ``dt`` apart, off by at most about
    ``(omega dt)^2 dt / 6`` each; the fitted period over ``t_end`` by that over ``t_end``.
    CFOAM keeps terms beyond its linearisation (FOAM's) that are products of the steady axial
    stretch ``q1s`` with the deflection (the foreshortening of the stretched beam): a relative
    change of the order of the stretch ``f1(L) q1s / L``, which joins its tolerance."""
    params, numerics = setup
    params = dataclasses.replace(params, Jh=1e9)
    traits = MODELS[model]
    sm = matrices(spin_case(model, {}), params, numerics)
    x0, v0, expected = _linear_mode(sm, traits.linearisation, traits.keeps_axial)
    n = 2
    q1, q2 = (x0[:n], x0[n:]) if traits.keeps_axial else (np.zeros(n), x0)
    q1d, q2d = (v0[:n], v0[n:]) if traits.keeps_axial else (np.zeros(n), v0)
    scale = 1e-5 * params.L
    initial = {"hub_speed": SPEED, "q1": list(scale * q1), "q2": list(scale * q2),
               "q1_dot": list(scale * q1d), "q2_dot": list(scale * q2d)}
    if not traits.keeps_axial:
        del initial["q1"], initial["q1_dot"]
    t_end = 12 * 2 * np.pi / expected
    ds = simulate(spin_case(model, initial, t_end=t_end), params, numerics)
    tip = ds["tip_transverse"].values
    t = ds["time"].values
    k = np.flatnonzero(np.sign(tip[:-1]) != np.sign(tip[1:]))
    crossings = t[k] - tip[k] * (t[k + 1] - t[k]) / (tip[k + 1] - tip[k])
    half_period = np.polyfit(np.arange(crossings.size), crossings, 1)[0]
    measured = np.pi / half_period
    linear = linearised.frequencies(sm, traits.linearisation, SPEED, traits.keeps_axial)[0]
    assert linear == pytest.approx(expected, rel=1e-9)
    dt = numerics["output_step"]
    tolerance = (10 * float(sm.V2 @ sm.V2) / params.Jh + numerics["rtol"]
                 + (expected * dt) ** 2 * dt / 6 / t_end)
    if traits.exact_kinetic_energy:
        tolerance += abs(sm.f1L @ linearised.axial_stretch(sm, SPEED)) / params.L
    assert measured == pytest.approx(linear, rel=tolerance)


def test_a_prescribed_hub_starts_at_its_maneuver_speed(setup):
    params, numerics = setup
    steady = {"kind": "speed_table", "time": [0.0, 5.0], "speed": [SPEED, SPEED]}
    ds = simulate(spin_case("FOAM", {"hub_speed": SPEED}, t_end=5.0, maneuver=steady), params,
                  numerics)
    sm = matrices(spin_case("FOAM", {}), params, numerics)
    np.testing.assert_allclose(ds["q2"], 0.0, atol=numerics["atol"])
    np.testing.assert_allclose(ds["q1"], np.broadcast_to(linearised.axial_stretch(sm, SPEED), (ds.time.size, 2)),
                               rtol=numerics["rtol"], atol=numerics["atol"])
    spin_up = {"kind": "prescribed", "wf": 3.0, "tf": 30.0}
    with pytest.raises(ConfigError, match=r"cases.spin_FOAM.initial.hub_speed: got 2.0; allowed: "
                                          r"0.0 rad s-1, the speed at t = 0 of the prescribed"):
        simulate(spin_case("FOAM", {"hub_speed": SPEED}, maneuver=spin_up), params, numerics)


def test_the_initial_state_is_recorded_and_reproduced(setup):
    params, numerics = setup
    case = spin_case("SFOAM", {"hub_speed": 1.0, "q2": [1e-3, 0.0]}, t_end=2.0)
    ds = simulate(case, params, numerics)
    again = simulate(**simulation_inputs(ds.attrs))
    np.testing.assert_array_equal(again["tip_transverse"], ds["tip_transverse"])
    assert ds["theta_dot"][0] == 1.0 and ds["q2"][0, 0] == 1e-3


@pytest.mark.parametrize("initial, key", [
    ([1.0], "initial"),
    ({"speed": 1.0}, "initial.speed"),
    ({"q2": ["a", 0.0]}, "initial.q2[0]"),
    ({"hub_speed": float("nan")}, "initial.hub_speed"),
])
def test_initial_states_of_the_wrong_form_are_rejected_by_the_configuration_check(setup, initial, key):
    params, numerics = setup
    with pytest.raises(ConfigError) as error:
        simulate(spin_case("FOAM", initial), params, numerics)
    (problem,) = error.value.problems
    assert problem.path == f"cases.spin_FOAM.{key}", problem


@pytest.mark.parametrize("model, initial, message", [
    ("FOAM", {"q2": [0.0]}, r"initial.q2: got \[0.0\]; allowed: a list of 2 numbers, one per mode"),
    ("SFOAM", {"q1": [0.0, 1e-3]}, r"initial.q1: got \[0.0, 0.001\]; allowed: zeros or no q1: SFOAM keeps no axial"),
])
def test_impossible_initial_states_are_rejected_naming_the_key(setup, model, initial, message):
    params, numerics = setup
    with pytest.raises(ConfigError, match=message) as error:
        simulate(spin_case(model, initial), params, numerics)
    (problem,) = error.value.problems
    assert problem.path == f"cases.spin_{model}.initial.{next(iter(initial))}", problem


def test_the_convergence_rerun_with_more_modes_starts_from_the_padded_initial_state(setup):
    """The rerun with one more mode takes the case's initial modal values with the added mode at
    rest (a list of the wrong length would be rejected) and runs to the end."""
    params, numerics = setup
    check = {"tolerance_factor": 0.1, "extra_modes": 1, "threshold_m": 1e-6}
    ds = simulate(spin_case("FOAM", {"hub_speed": SPEED, "q2": [1e-3, 0.0]}, t_end=1.0), params,
                  numerics, convergence_check=check)
    assert np.isfinite(ds.attrs["convergence_modes_diff_m"])
