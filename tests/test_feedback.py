"""State feedback on the free hub (``maneuver.kind: state_feedback``, ``hubbeam.control.feedback``).

* PD is state feedback on the hub angle and speed only: the same run to rounding;
* about a steady spin, a controller designed by LQR on model X and run on X is stable, and the
  nonlinear closed loop from a small deviation follows the linear closed loop ``A - B K`` (its
  poles, which the dataset records): the equations' nonlinear terms are quadratic, so the
  difference falls to a quarter (within 12 %) when the amplitude halves, and is below 1 % of the
  response at 1 cm of modal amplitude (measured 0.2 %);
* from the steady spin plus a small deviation along the least-damped closed-loop mode the tip
  sees, the decay rate and damped frequency fitted to the nonlinear tip deflection are those of
  its pole of ``A - B K`` within the relative size of the neglected terms, the error halving
  with the amplitude;
* the LQR cost ``x0' P x0`` equals the cost integrated along the nonlinear run within the
  relative size of the neglected terms (the tip deflection over the length), the relative
  difference halving with the amplitude;
* the work of the hub torque equals the change of energy plus the dissipation in closed loop;
* output feedback on the hub angle and speed is the PD hub again;
* bad input is refused before anything runs, naming the key.
"""

import dataclasses
import json

import numpy as np
import pytest
import scipy.linalg
from scipy.integrate import simpson

from hubbeam.configuration.settings import InitialState, simulation_settings
from hubbeam.control.cases import simulate_case
from hubbeam.control.feedback import lqr_design
from hubbeam.linear.statespace import linear_model
from hubbeam.model.modes import transverse_modes
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.measures import fit_decaying_sinusoid
from hubbeam.simulation.simulate import SimulationError, case_matrices

SPEED = 2.0  # rad s-1, the design speed (below TLAM's critical speed of this beam, 2.91 rad s-1)
DESIGN = {"speed": SPEED, "torque_weight": 1e-4,
          "weights": {"hub_angle": 100.0, "hub_speed": 10.0, "tip_deflection": 1e3}}
#: a reference at steady spin from t = 0: Eq. 43 over a vanishing tf (its angle lags by wf tf / 2;
#: the speed error while it lasts gives the hub a torque impulse K_theta_dot wf tf / 2, which at
#: tf = 1e-9 s moves the tip by about 4e-9 m, far below the second-order differences tested)
STEADY = {"kind": "prescribed", "wf": SPEED, "tf": 1e-9}


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), dict(_study_config["numerics"])


def _case(maneuver, model="FOAM", t_end=6.0, modes=2, **extra):
    return {"name": "sf", "model": model, "modes": modes, "t_end": t_end, "maneuver": maneuver,
            "tip_mass": {"mass": 0.0, "position": 8.0}, **extra}


def _objects(case, params, numerics):
    """The case and numerics mappings as the objects of the one check (``Case``, ``Numerics``)."""
    return simulation_settings(case, numerics, params.L)


def _matrices(case, params, numerics):
    """The system matrices of the case mapping ``case``."""
    case, numerics = _objects(case, params, numerics)
    return case_matrices(case, params, numerics)


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_pd_is_state_feedback_on_the_hub_angle_and_speed(setup, model):
    params, numerics = setup
    reference = {"kind": "prescribed", "wf": 1.0, "tf": 4.0}
    pd = simulate_case(_case({"kind": "pd", "kp": 400.0, "kd": 200.0, "reference": reference},
                             model), params, numerics)
    gains = {"kind": "state_feedback", "reference": reference,
             "gains": {"theta": 400.0, "theta_dot": 200.0}}
    outputs = {"kind": "state_feedback", "reference": reference,
               "output_feedback": {"hub_angle": 400.0, "hub_speed": 200.0}}
    for maneuver in (gains, outputs):
        sf = simulate_case(_case(maneuver, model), params, numerics)
        for name in ("theta", "tip_transverse", "hub_torque"):
            np.testing.assert_allclose(sf[name].values, pd[name].values, rtol=1e-12,
                                       atol=1e-12 * np.abs(pd[name].values).max())


def _steady_run(params, numerics, model, amplitude, t_end=8.0):
    maneuver = {"kind": "state_feedback", "reference": STEADY, "design": dict(DESIGN, model=model)}
    case = _case(maneuver, model, t_end=t_end,
                 initial={"hub_speed": SPEED, "q2": [amplitude, 0.0]})
    return case, simulate_case(case, params, dict(numerics, output_step=0.005))


def _linear_closed_loop(params, numerics, case, ds, amplitude):
    """The deviation ``x(t)`` of the linear closed loop from the run's initial deviation, and
    the LQR matrices, on the run's time grid."""
    sm = _matrices(case, params, numerics)
    lin = linear_model(params, sm, case["model"], SPEED, "free")
    K = np.array([list(json.loads(ds.attrs["feedback_gains"]).values())])
    P = np.array(json.loads(ds.attrs["feedback_design_riccati"]))
    x0 = np.zeros(lin.A.shape[0])
    x0[lin.states.index("q2_1")] = amplitude
    x0[0] = SPEED * STEADY["tf"] / 2  # theta - theta_r after the reference's vanishing spin-up
    Acl = lin.A - lin.B @ K
    t = ds.time.values
    x = np.array([scipy.linalg.expm(Acl * tk) @ x0 for tk in t])
    return lin, K, P, x0, x


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_small_motions_about_the_steady_spin_follow_the_linear_closed_loop(setup, model):
    params, numerics = setup
    numerics = dict(numerics, rtol=1e-10, atol=1e-12)
    errors = []
    for amplitude in (0.02, 0.01):
        case, ds = _steady_run(params, numerics, model, amplitude)
        lin, K, _, _, x = _linear_closed_loop(params, numerics, case, ds, amplitude)
        poles = np.array(json.loads(ds.attrs["feedback_design_poles"]))
        np.testing.assert_allclose(np.sort(poles[:, 0]), np.sort(np.linalg.eigvals(lin.A - lin.B @ K).real),
                                   rtol=1e-8)
        assert poles[:, 0].max() < 0.0  # designed on X, stable on X
        tip = lin.C[lin.outputs.index("tip_deflection")] @ x.T
        error = np.abs(ds.tip_transverse.values - tip).max()
        errors.append(error)
        assert error < 0.01 * np.abs(tip).max()
        late = ds.time.values > ds.time.values[-1] - 1.0
        assert np.abs(ds.tip_transverse.values[late]).max() < 0.2 * np.abs(tip).max()
    assert 3.5 < errors[0] / errors[1] < 4.5  # second order in the amplitude


def _least_damped_tip_mode(lin, K):
    """The closed-loop pole of ``A - B K`` (upper half plane) with the smallest decay rate among
    the oscillatory modes that move the tip (the undamped axial modes, out of the torque's reach,
    barely do), and its eigenvector ``v``, scaled so that the real initial deviation ``Re(v)``
    has a unit tip deflection and no hub angle (a run starts at ``theta = 0``)."""
    poles, vectors = np.linalg.eig(lin.A - lin.B @ K)
    tip = lin.C[lin.outputs.index("tip_deflection")]
    share = np.abs(tip @ vectors) / np.abs(vectors).max(axis=0)
    modes = [k for k in range(len(poles)) if poles[k].imag > 0 and share[k] > 1e-2 * share.max()]
    k = max(modes, key=lambda k: poles[k].real)
    v = 1j * vectors[:, k] / vectors[0, k]  # theta purely imaginary: Re(v) has theta = 0
    return poles[k], v / (tip @ v.real)


def _initial_from_deviation(lin, x0, n):
    """A case's ``initial`` mapping for the steady spin plus the linear model's deviation ``x0``
    (``theta = 0`` there; ``q1`` is added to the centrifugal stretch as in the linear model)."""
    assert x0[lin.states.index("theta")] == 0.0
    initial = {"hub_speed": SPEED + float(x0[lin.states.index("theta_dot")])}
    for key, suffix in (("q1", ""), ("q2", ""), ("q1_dot", "_dot"), ("q2_dot", "_dot")):
        names = [f"{key[:2]}_{i}{suffix}" for i in range(1, n + 1)]
        if names[0] in lin.states:
            initial[key] = [float(x0[lin.states.index(name)]) for name in names]
    return initial


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_decay_rate_and_frequency_of_the_nonlinear_loop_are_its_linear_pole(setup, model):
    """The linear closed loop from ``a Re(v)`` is ``a Re(v exp(p t))``: its tip deflection one
    decaying sinusoid, which the fit recovers to rounding on any grid and window (the integrator's
    rtol 1e-10 adds as little), so what remains is the nonlinear terms' share. Neglected, they
    are of relative size v(L) / L (as for the LQR cost), and they move the fitted pole by that
    relative size times an order-one factor (measured 0.7 for the frequency, 0.1 for the decay
    rate), a shift of first order in the amplitude."""
    params, numerics = setup
    numerics = dict(numerics, rtol=1e-10, atol=1e-12, output_step=0.005)
    maneuver = {"kind": "state_feedback", "reference": STEADY, "design": dict(DESIGN, model=model)}
    case, checked = _objects(_case(maneuver, model, t_end=8.0), params, numerics)
    sm = case_matrices(case, params, checked)
    lin = linear_model(params, sm, model, SPEED, "free")
    gains, _ = lqr_design(case, params, sm)
    assert list(gains) == list(lin.states)
    pole, v = _least_damped_tip_mode(lin, np.array([list(gains.values())]))
    t = np.arange(0.0, 8.0, 0.005)
    tip = lin.C[lin.outputs.index("tip_deflection")] @ v
    linear = fit_decaying_sinusoid(t, (tip * np.exp(pole * t)).real, 0.0)
    assert (linear.decay_rate, linear.omega) == (pytest.approx(-pole.real, rel=1e-9),
                                                 pytest.approx(pole.imag, rel=1e-9))
    errors = []
    for amplitude in (0.02, 0.01):
        initial = InitialState.from_dict(_initial_from_deviation(lin, amplitude * v.real, 2))
        ds = simulate_case(dataclasses.replace(case, initial=initial), params, checked)
        fit = fit_decaying_sinusoid(ds.time.values, ds.tip_transverse.values, 0.0)
        error = max(abs(fit.decay_rate + pole.real), abs(fit.omega - pole.imag)) / abs(pole)
        errors.append(error)
        assert error < np.abs(ds.tip_transverse.values).max() / params.L
    assert 1.6 < errors[0] / errors[1] < 2.4  # first order in the amplitude


def test_the_lqr_cost_is_the_cost_along_the_nonlinear_run(setup):
    params, numerics = setup
    numerics = dict(numerics, rtol=1e-10, atol=1e-12)
    gaps, ratios = [], []
    for amplitude in (0.02, 0.01):
        case, ds = _steady_run(params, numerics, "FOAM", amplitude, t_end=20.0)
        lin, K, P, x0, _ = _linear_closed_loop(params, numerics, case, ds, amplitude)
        t = ds.time.values
        torque = ds.hub_torque.values.copy()
        torque[0] = -(K @ x0)[0]  # at t = 0 the sample holds the reference's vanishing spin-up
        theta_r = SPEED * (t - STEADY["tf"] / 2)
        w = DESIGN["weights"]
        sm = _matrices(case, params, numerics)
        running = (w["hub_angle"] * (ds.theta.values - theta_r) ** 2
                   + w["hub_speed"] * (ds.theta_dot.values - SPEED) ** 2
                   + w["tip_deflection"] * (ds.q2.values @ sm.f2L) ** 2
                   + DESIGN["torque_weight"] * torque ** 2)
        cost = simpson(running, x=t)
        expected = x0 @ P @ x0
        gaps.append(abs(cost - expected) / expected)
        ratios.append(np.abs(ds.tip_transverse.values).max() / params.L)
    # the neglected terms are of the relative size of the deflection over the length (measured
    # 6e-5 at the larger amplitude, where v(L) / L = 4e-3)
    assert gaps[0] < ratios[0]
    assert 1.6 < gaps[0] / gaps[1] < 2.4  # the relative gap is of first order in the amplitude


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
def test_work_of_the_hub_torque_is_energy_change_plus_dissipation(setup, model):
    """Simpson's rule on the 0.005 s grid as for the open-loop maneuvers (measured about 1e-9 of
    the largest work there); damping on, so the dissipation enters."""
    params, numerics = setup
    maneuver = {"kind": "state_feedback", "feedforward": True,
                "reference": {"kind": "prescribed", "wf": 1.0, "tf": 4.0},
                "design": dict(DESIGN, model="FOAM", speed=1.0)}
    ds = simulate_case(_case(maneuver, model, damping={"kind": "modal", "axial": 0.02, "transverse": 0.02}), params,
                       dict(numerics, output_step=0.005))
    change = ds.energy.values - ds.energy.values[0]
    work = ds.work.values
    assert np.abs(work).max() > 1.0 and ds.dissipated_energy.values[-1] > 0.0
    np.testing.assert_allclose(change + ds.dissipated_energy.values, work, rtol=0,
                               atol=1e-7 * np.abs(work).max())


@pytest.mark.parametrize("maneuver, words", [
    ({"gains": {"q2_3": 1.0}}, ["maneuver.gains.q2_3", "allowed: theta, q1_1"]),
    ({"gains": {"q1_1": 1.0}}, ["maneuver.gains.q1_1", "allowed: theta, q2_1"]),
    ({"design": dict(DESIGN, model="FOAM", weights={"q2_1": -1.0})}, ["weights.q2_1", "-1.0"]),
    ({"design": dict(DESIGN, model="FOAM", torque_weight=0.0)}, ["torque_weight", "0"]),
    ({"design": dict(DESIGN, model="XFOAM")}, ["design.model", "XFOAM"]),
    ({"design": dict(DESIGN, model="FOAM", speed=1e4)}, ["maneuver.design.speed: got 10000.0", "steady state"]),
    ({"feedforward": True, "gains": {"theta": 1.0},
      "reference": {"kind": "angle_table", "time": [0.0, 1.0], "angle": [0.0, 1.0]}},
     ["maneuver.feedforward: got true", "angle_table"]),
])
def test_bad_feedback_input_is_refused_naming_the_key(setup, maneuver, words):
    params, numerics = setup
    model = "SFOAM" if "q1_1" in maneuver.get("gains", {}) else "FOAM"
    full = {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.0, "tf": 4.0},
            **maneuver}
    with pytest.raises(ValueError) as error:
        simulate_case(_case(full, model, t_end=0.1), params, numerics)
    for word in words:
        assert word in str(error.value)



def test_a_plant_the_torque_cannot_stabilise_is_refused_naming_the_mode(setup):
    """At rest FOAM's axial modes decouple from the hub (no Coriolis coupling, M_thq1 = 0): without
    damping they sit on the imaginary axis out of the torque's reach (PBH), so no design there;
    with axial damping they are stable and the design goes ahead."""
    params, numerics = setup
    maneuver = {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.0, "tf": 4.0},
                "design": dict(DESIGN, model="FOAM", speed=0.0)}
    with pytest.raises(SimulationError) as error:
        simulate_case(_case(maneuver, t_end=0.1), params, numerics)
    assert "not stabilisable from the hub torque" in str(error.value)
    assert "mostly q1_" in str(error.value) and "design.model: got 'FOAM' at speed 0.0" in str(error.value)
    damped = _case(maneuver, t_end=0.1, damping={"kind": "modal", "axial": 0.01, "transverse": 0.0})
    assert simulate_case(damped, params, numerics).attrs["integrator_status"] == "success"


def test_feedback_of_the_root_moment_is_feedback_of_the_curvature_at_the_root(setup):
    """The measured root bending moment EI(0) v''(0) = EI(0) f2''(0) q2 (a strain gauge) fed back
    with gain k is state feedback with the gains k EI(0) f2''(0) on q2 (the mode shapes' second
    derivative at the root computed here on its own)."""
    params, numerics = setup
    reference = {"kind": "prescribed", "wf": 1.0, "tf": 4.0}
    k = 0.05
    curvature = float(params.EI_at(0.0)) * transverse_modes(0.0, 2, params, derivative=2)[0]
    measured = {"kind": "state_feedback", "reference": reference,
                "output_feedback": {"hub_angle": 400.0, "hub_speed": 200.0, "root_moment": k}}
    gains = {"kind": "state_feedback", "reference": reference,
             "gains": {"theta": 400.0, "theta_dot": 200.0, "q2_1": k * curvature[0], "q2_2": k * curvature[1]}}
    a, b = (simulate_case(_case(maneuver), params, numerics) for maneuver in (measured, gains))
    assert np.abs(a.tip_transverse.values - _case_pd_tip(params, numerics, reference)).max() > 1e-4
    for name in ("theta", "tip_transverse", "hub_torque"):
        np.testing.assert_allclose(a[name].values, b[name].values, rtol=1e-9,
                                   atol=1e-9 * np.abs(b[name].values).max())


def _case_pd_tip(params, numerics, reference):
    """The tip deflection of the same loop without the root moment (the gain must matter)."""
    pd = {"kind": "pd", "kp": 400.0, "kd": 200.0, "reference": reference}
    return simulate_case(_case(pd), params, numerics).tip_transverse.values
