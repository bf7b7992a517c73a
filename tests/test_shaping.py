"""Shaped commands on the hub-beam: the kernels (hubbeam.core.shaping), the tuning from the
linear models (hubbeam.control.shaping) and the nonlinear runs.

* The identity shaper (the kernels' default) returns every maneuver's command to the bit, so
  unshaped runs do not move; a three-impulse shaper returns the weighted sum of the delayed
  commands, and a controller's law acts on the shaped reference (the state feedback's stretch on
  the square of the shaped speed).
* The integrator's stops hold every shifted discontinuity.
* Tuning: the held hub's first mode at rest is the cantilever's (Euler-Bernoulli, ``(1.8751)^2
  sqrt(EI / rho A L^4)``) with the modal damping given; a stiff position servo's closed-loop
  bending mode tends to the held hub's as ``1 / kp``; the closed loop's eigenvalue is among the
  poles python-control's ``feedback`` gives; a maneuver picks its loop; what does not exist is
  refused.
* FOAM spin-up (Eq. 43) with 0.5 % modal damping: a ZV, ZVD or EI shaper tuned on FOAM's held-hub
  first mode at the final speed cuts the residual tip vibration by the linear factor ``V``
  within ``delta = 1 - (omega(0) / omega(wf))^2``, the share of the mode's stiffness that the
  spin-up adds (dynamic stiffening): the linear prediction takes the mode at the final speed,
  while the shaped command acts as the stiffness grows from ``omega(0)^2``. The deviation is of
  first order in ``delta`` (quadratic in ``wf``): halving ``wf`` divides it as ``delta``.
* Shaping commutes with the kernel: a shaped Eq. 43 run equals a speed-table run of the shaped
  speed (computed here in numpy), to the interpolation error of the table's clamped cubic spline.
"""

import functools
import math

import numpy as np
import pytest

from hubbeam.configuration.settings import simulation_settings
from hubbeam.control.cases import resolve
from hubbeam.control.feedback import coordinate_names
from hubbeam.control.shaping import case_shaping_mode, linear_shaping_mode, maneuver_loop
from hubbeam.core.inputs import IDENTITY_SHAPER
from hubbeam.core.maneuver import (
    open_loop_torque,
    prescribed,
    prescribed_motion,
    reference_motion,
    reference_offset,
    tracking_torque,
    tracks_reference,
)
from hubbeam.core.shaping import shaped_motion, shaped_torque
from hubbeam.linear.statespace import linear_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.eigen import critical_speed
from hubbeam.model.maneuvers import FeedbackLaw, maneuver_from_dict
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters
from hubbeam.model.shapers import DESIGNS, Shaper, residual_vibration
from hubbeam.results.measures import residual_amplitude, shaped_residual_amplitude
from hubbeam.simulation.simulate import Resolved, output_times, simulate, step_stops

ANGLE_TABLE = {"kind": "angle_table", "time": [0.5, 2.0, 5.0], "angle": [0.2, 1.0, 1.5]}
#: every maneuver kind, tables that start after t = 0 and away from rest
MANEUVERS = {
    "prescribed": {"kind": "prescribed", "wf": 1.5, "tf": 4.0},
    "speed_table": {"kind": "speed_table", "time": [0.5, 2.0, 5.0], "speed": [0.3, 1.0, 0.8]},
    "torque": {"kind": "torque", "tau_max": 30.0, "tf": 3.0},
    "torque_table": {"kind": "torque_table", "time": [0.5, 2.0, 5.0], "torque": [5.0, -20.0, 3.0]},
    "pd_prescribed": {"kind": "pd", "kp": 300.0, "kd": 90.0,
                      "reference": {"kind": "prescribed", "wf": 1.5, "tf": 4.0}},
    "pd_table": {"kind": "pd", "kp": 300.0, "kd": 90.0, "reference": ANGLE_TABLE},
    "feedback": {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.5, "tf": 4.0}},
    "feedback_table": {"kind": "state_feedback", "reference": ANGLE_TABLE},
}
N_MODES = 2
#: a state feedback law on (theta, q1, q2) and rates with every gain, a stretch and a feedforward
LAW = FeedbackLaw(np.array([300.0, 12.0, -4.0, 40.0, 7.0, 90.0, 0.5, 0.2, 3.0, -1.0]),
                  np.array([0.02, -0.003]), 210.0)
THREE = Shaper([0.0, 0.7, 1.9], [0.3, 0.5, 0.2], "three impulses")
TIMES = np.concatenate([np.linspace(-1.0, 9.0, 401), [0.0, 0.5, 2.0, 3.0, 4.0, 5.0, 4.7, 5.9]])


def _parameters(maneuver):
    law = FeedbackLaw(LAW.gains, LAW.stretch, 0.0) if maneuver.get("reference") is ANGLE_TABLE else LAW
    return maneuver_from_dict(maneuver).kernel_parameters(law if maneuver["kind"] == "state_feedback" else None)


def _states(n_coordinates):
    rng = np.random.default_rng(5)
    return rng.normal(size=n_coordinates), rng.normal(size=n_coordinates)


@pytest.mark.parametrize("name", MANEUVERS)
def test_the_identity_shaper_returns_every_command_to_the_bit(name):
    kind, mp = _parameters(MANEUVERS[name])
    for t in TIMES:
        if prescribed(kind):
            got, expected = shaped_motion(kind, t, mp, IDENTITY_SHAPER), prescribed_motion(kind, t, mp)
        else:
            # the full coordinates, and those of a model without q1 (SFOAM)
            for size in (1 + 2 * N_MODES, 1 + N_MODES):
                y, v = _states(size)
                got = shaped_torque(kind, t, y, v, mp, IDENTITY_SHAPER, 0)
                expected = (tracking_torque(kind, reference_motion(t, mp, reference_offset(kind, mp)), y, v, mp, 0)
                            if tracks_reference(kind) else open_loop_torque(kind, t, mp))
                assert np.array(got).tobytes() == np.array(expected).tobytes()
            continue
        assert np.array(got).tobytes() == np.array(expected).tobytes()


def _hand_law(reference, y, v, maneuver):
    """The controller's torque written out from the maneuver's settings (not from ``mp``)."""
    theta_r, rate_r, acceleration_r = reference
    if maneuver["kind"] == "pd":
        return maneuver["kp"] * (theta_r - y[0]) + maneuver["kd"] * (rate_r - v[0])
    inertia = 0.0 if maneuver["reference"] is ANGLE_TABLE else LAW.inertia
    n = N_MODES
    target = np.concatenate([[theta_r], rate_r**2 * LAW.stretch, np.zeros(n)])
    target_rate = np.concatenate([[rate_r], np.zeros(2 * n)])
    N = 1 + 2 * n
    return (inertia * acceleration_r - LAW.gains[:N] @ (y - target)
            - LAW.gains[N:] @ (v - target_rate))


@pytest.mark.parametrize("name", MANEUVERS)
def test_a_shaped_command_is_the_weighted_sum_of_the_delayed_commands(name):
    maneuver = MANEUVERS[name]
    kind, mp = _parameters(maneuver)
    shaper = THREE.kernel_array()
    y, v = _states(1 + 2 * N_MODES)
    for t in TIMES:
        delayed = [(a, t - ti) for ti, a in zip(THREE.times, THREE.amplitudes)]
        if prescribed(kind):
            expected = sum(a * np.array(prescribed_motion(kind, s, mp)) for a, s in delayed)
            np.testing.assert_allclose(shaped_motion(kind, t, mp, shaper), expected, rtol=1e-14, atol=1e-14)
        elif "reference" in maneuver:  # the law towards the shaped reference, at the present state
            o = reference_offset(kind, mp)
            reference = sum(a * np.array(reference_motion(s, mp, o)) for a, s in delayed)
            expected = _hand_law(reference, y, v, maneuver)
            assert shaped_torque(kind, t, y, v, mp, shaper, 0) == pytest.approx(expected, rel=1e-12, abs=1e-12)
        else:
            expected = sum(a * open_loop_torque(kind, s, mp) for a, s in delayed)
            assert shaped_torque(kind, t, y, v, mp, shaper, 0) == pytest.approx(expected, rel=1e-14, abs=1e-14)


@pytest.mark.parametrize("name", MANEUVERS)
def test_no_step_crosses_a_shifted_discontinuity(name):
    maneuver = MANEUVERS[name]
    record = maneuver_from_dict(maneuver)
    t = output_times(12.0, 0.01)
    stops = step_stops(record, t, THREE)
    source = maneuver.get("reference", maneuver)
    edges = [0.0, *([source["tf"]] if "tf" in source else source["time"])]
    for edge in edges:
        for delay in THREE.times:
            if 0.0 < edge + delay < t[-1]:
                assert np.any(np.isclose(stops, edge + delay, rtol=0, atol=1e-12)), (edge, delay)
    assert np.all(np.diff(stops) > 0.0) and stops[0] > 0.0 and stops[-1] < t[-1]
    np.testing.assert_array_equal(step_stops(record, t), step_stops(record, t, None))


@pytest.fixture(scope="module")
def setup(_study_config):
    numerics = dict(_study_config["numerics"])
    numerics.pop("convergence_check")
    return BeamParameters.from_config(_study_config), numerics


@pytest.fixture(scope="module")
def matrices(setup):
    return assemble(setup[0], None, 3, 64)


#: the first root of 1 + cos z cosh z = 0 (clamped-free Euler-Bernoulli beam)
BETA_1 = 1.8751040687119611


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "SFOAM", "CFOAM"])
def test_held_hub_first_mode_at_rest_is_the_cantilevers(setup, matrices, model):
    params = setup[0]
    cantilever = BETA_1**2 * math.sqrt(params.E * params.I / (params.rho * params.A * params.L**4))
    mode = linear_shaping_mode(params, matrices, model, 0.0, "held")
    assert mode.label == "bending 1"
    assert mode.omega == pytest.approx(cantilever, rel=1e-9)  # the basis holds the exact mode
    assert mode.zeta == pytest.approx(0.0, abs=1e-12)  # undamped: Re(lambda) below 2e-12 s-1 (tracking)
    damping = damping_matrices({"kind": "modal", "axial": 0.01, "transverse": 0.02}, matrices)
    damped = linear_shaping_mode(params, matrices, model, 0.0, "held", damping=damping)
    assert (damped.omega, damped.zeta) == pytest.approx((cantilever, 0.02), rel=1e-9)


def test_a_stiff_position_servo_holds_the_hub(setup, matrices):
    params = setup[0]
    held = linear_shaping_mode(params, matrices, "FOAM", 1.0, "held", mode="bending 1")
    gaps = []
    for kp in (1e6, 1e7, 1e8):  # kd = 2 sqrt(kp Jh): about critically damped (Jh + Jb = 241 kg m2)
        gains = {"theta": kp, "theta_dot": 2.0 * math.sqrt(kp * 200.0)}
        closed = linear_shaping_mode(params, matrices, "FOAM", 1.0, "closed", mode="bending 1", gains=gains)
        gaps.append(abs(closed.omega - held.omega) / held.omega)
    assert gaps[0] < 1e-3
    # first order in 1 / kp: a tenfold stiffer servo, a tenfold smaller gap; within 1 %, the next
    # order's share (0.5 % at kp = 1e6, tenfold less per decade)
    assert gaps[1] / gaps[0] == pytest.approx(0.1, rel=0.01)
    assert gaps[2] / gaps[1] == pytest.approx(0.1, rel=0.01)


def test_closed_loop_mode_is_a_pole_of_python_controls_feedback(setup, matrices):
    import control as ct

    params = setup[0]
    lin = linear_model(params, matrices, "FOAM", 1.0, "free")
    K = ct.lqr(lin.A, lin.B, np.eye(lin.A.shape[0]), 1e-4)[0]  # a stabilising gain on every state
    gains = dict(zip(lin.states, K[0].tolist()))
    loop = ct.feedback(ct.ss(lin.A, lin.B, np.eye(lin.A.shape[0]), 0.0), K)
    poles = ct.poles(loop)
    for mode in (1, 2, "bending 2"):
        found = linear_shaping_mode(params, matrices, "FOAM", 1.0, "closed", mode=mode, gains=gains)
        assert np.min(np.abs(poles - found.eigenvalue)) < 1e-9 * abs(found.eigenvalue)
        assert found.omega == pytest.approx(abs(found.eigenvalue), rel=1e-15)


def _checked(case):
    """The case mapping as the one check of the configuration hands it on (a ``Case``)."""
    return simulation_settings(case, {"output_step": 0.01}, 8.0)[0]


def test_a_maneuver_picks_the_loop_its_command_drives(setup, matrices):
    params = setup[0]
    case = {"name": "tuning", "model": "FOAM", "modes": 3, "t_end": 5.0,
            "tip_mass": {"mass": 0.0, "position": 8.0},
            "damping": {"kind": "modal", "axial": 0.01, "transverse": 0.01}}
    damping = damping_matrices(case["damping"], matrices)
    expected = {"prescribed": ("held", None), "speed_table": ("held", None),
                "torque": ("free", None), "torque_table": ("free", None),
                "pd_table": ("closed", {"theta": 300.0, "theta_dot": 90.0})}
    for name, (loop, gains) in expected.items():
        maneuver = MANEUVERS[name]
        assert maneuver_loop(maneuver_from_dict(maneuver)) == loop
        found = case_shaping_mode(_checked(dict(case, maneuver=maneuver)), params, matrices, 1.0)
        assert found == linear_shaping_mode(params, matrices, "FOAM", 1.0, loop, damping=damping, gains=gains)
    feedback = dict(case, maneuver={"kind": "state_feedback", "reference": ANGLE_TABLE,
                                    "gains": {"theta": 300.0, "theta_dot": 90.0, "q1_1": 2.0}})
    gains = {"theta": 300.0, "theta_dot": 90.0, "q1_1": 2.0}
    assert case_shaping_mode(_checked(feedback), params, matrices, 1.0, mode=2) == linear_shaping_mode(
        params, matrices, "FOAM", 1.0, "closed", mode=2, damping=damping, gains=gains)
    assert set(gains) <= set(coordinate_names(3))


def test_modes_that_do_not_exist_are_refused(setup, matrices):
    params = setup[0]
    beyond = 1.1 * critical_speed("TLAM", params, None, 3, 20.0)
    with pytest.raises(ValueError, match="TLAM.*growing mode"):
        linear_shaping_mode(params, matrices, "TLAM", beyond, "held")
    with pytest.raises(ValueError, match=r"mode = 7: .* has 6 vibration modes .*allowed: 1\.\.6"):
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "held", mode=7)
    with pytest.raises(ValueError, match="mode = 'bending 4'"):
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "held", mode="bending 4")
    with pytest.raises(ValueError, match="mode = 0"):
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "held", mode=0)
    with pytest.raises(ValueError, match="loop = 'open'"):
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "open")
    with pytest.raises(ValueError, match="gains = None with loop = 'closed'"):
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "closed")
    with pytest.raises(ValueError, match="gains.q1_1 = 2.0: SFOAM has no such state"):
        linear_shaping_mode(params, matrices, "SFOAM", 1.0, "closed", gains={"theta": 1.0, "q1_1": 2.0})
    with pytest.raises(ValueError, match="growing mode"):  # a destabilising loop
        linear_shaping_mode(params, matrices, "FOAM", 1.0, "closed", gains={"theta": -10.0})


#: 0.5 % modal damping: the residual decays by 3 % per period of the first mode
LIGHT = {"kind": "modal", "axial": 0.005, "transverse": 0.005}
SPIN_UP_TIME = 5.0  # s, not a multiple of the first period (2.1 s): the unshaped spin-up leaves vibration


def _spin_up(wf, t_end):
    return {"name": "shaped", "model": "FOAM", "modes": 3, "t_end": t_end,
            "tip_mass": {"mass": 0.0, "position": 8.0}, "damping": LIGHT,
            "maneuver": {"kind": "prescribed", "wf": wf, "tf": SPIN_UP_TIME}}


@pytest.fixture(scope="module")
def residual_cuts(setup, matrices):
    """For each final speed and design: the measured ratio of the residual tip vibration (shaped
    over unshaped, each after its own command), the linear prediction ``V`` and ``delta``."""
    params, numerics = setup
    C = damping_matrices(LIGHT, matrices)
    found = {}
    for wf in (1.0, 0.5):
        mode = linear_shaping_mode(params, matrices, "FOAM", wf, "held", damping=C)
        rest = linear_shaping_mode(params, matrices, "FOAM", 0.0, "held", damping=C)
        delta = 1.0 - (rest.omega / mode.omega) ** 2
        t_end = SPIN_UP_TIME + 2.2 + 12.0  # the longest shaper (ZVD, EI) lasts one period, 2.1 s
        unshaped = simulate(_spin_up(wf, t_end), params, numerics)
        before = residual_amplitude(unshaped.time, unshaped.tip_transverse, SPIN_UP_TIME)
        for design in DESIGNS:
            shaper = DESIGNS[design](mode.omega, mode.zeta)
            run = simulate(_spin_up(wf, t_end), params, numerics, resolve=shaped(shaper))
            after = shaped_residual_amplitude(run.time, run.tip_transverse, SPIN_UP_TIME, shaper.duration)
            found[wf, design] = (after / before, residual_vibration(shaper, mode.omega, mode.zeta), delta)
    return found


@pytest.mark.parametrize("design", DESIGNS)
def test_a_shaper_tuned_on_foam_cuts_the_residual_by_the_linear_factor(residual_cuts, design):
    for wf in (1.0, 0.5):
        ratio, predicted, delta = residual_cuts[wf, design]
        assert abs(ratio - predicted) <= delta, (wf, ratio, predicted, delta)
    # the deviation is of first order in delta: halving wf divides both alike (within 15 %: the
    # second order, delta(1) = 3.3 %, and the window maxima, each up to 2 pi zeta = 3 % below the
    # envelope, four of them in this ratio)
    deviation = {wf: abs(residual_cuts[wf, design][0] - residual_cuts[wf, design][1]) for wf in (1.0, 0.5)}
    shrink = residual_cuts[0.5, design][2] / residual_cuts[1.0, design][2]
    assert deviation[0.5] / deviation[1.0] == pytest.approx(shrink, rel=0.15)


def _eq43_speed(t, wf, tf):
    """The speed of Eq. (43), written here (rest before 0, wf after tf)."""
    s = np.clip(t, 0.0, tf)
    return wf / tf * s - wf / (2.0 * np.pi) * np.sin(2.0 * np.pi * s / tf)


def test_shaping_commutes_with_the_kernel(setup, matrices):
    """A shaped Eq. 43 run against speed-table runs of the shaped speed, sampled every ``h`` with
    rows at every joint ``t_i``, ``tf + t_i`` (where the speed's third derivative jumps: between
    rows it is as smooth as the bounds assume). The clamped cubic spline of the speed (zero slope
    at both ends, as the shaped speed has) is off by at most ``5/384 h^4 max|f''''|`` in the speed
    and ``1/24 h^3 max|f''''|`` in its derivative, the hub acceleration (Hall & Meyer 1976),
    ``f'''' = wf (2 pi / tf)^3 / tf`` at most; the tip deflection, driven by the acceleration,
    converges as fast (by at least 8 per halving of h)."""
    params, numerics = setup
    wf, tf = 1.0, SPIN_UP_TIME
    mode = linear_shaping_mode(params, matrices, "FOAM", wf, "held")
    shaper = DESIGNS["ZV"](mode.omega, mode.zeta)
    case = {"name": "commute", "model": "FOAM", "modes": 3, "t_end": 12.0,
            "tip_mass": {"mass": 0.0, "position": 8.0}, "maneuver": {"kind": "prescribed", "wf": wf, "tf": tf}}
    commuted = simulate(case, params, numerics, resolve=shaped(shaper))

    def speed(t):
        return sum(a * _eq43_speed(t - ti, wf, tf) for ti, a in zip(shaper.times, shaper.amplitudes))

    # the kernel's shaped speed is the weighted sum of delayed Eq. 43 speeds
    np.testing.assert_allclose(commuted.theta_dot, speed(commuted.time.values), rtol=0, atol=1e-15 * wf)
    fourth = wf * (2.0 * np.pi / tf) ** 3 / tf
    end = tf + shaper.duration
    tip = []
    for h in (0.2, 0.1):
        rows = np.union1d(np.append(np.arange(0.0, end, h), end), np.concatenate([shaper.times, tf + shaper.times]))
        table = dict(case, maneuver={"kind": "speed_table", "time": rows.tolist(), "speed": speed(rows).tolist()})
        run = simulate(table, params, numerics)
        step = np.diff(rows).max()
        assert np.max(np.abs(run.theta_dot.values - commuted.theta_dot.values)) <= 5.0 / 384.0 * step**4 * fourth
        assert np.max(np.abs(run.theta_ddot.values - commuted.theta_ddot.values)) <= step**3 / 24.0 * fourth
        tip.append(float(np.max(np.abs(run.tip_transverse.values - commuted.tip_transverse.values))))
    assert tip[0] / tip[1] >= 8.0


def shaped(shaper):
    """A resolver that shapes a case's command with ``shaper`` (``simulate``'s ``resolve``)."""
    return lambda case, sm: Resolved(shaper=shaper)


def test_a_shaped_run_records_its_shaper_and_a_state_feedback_takes_one(setup):
    params, numerics = setup
    case = {"name": "pd", "model": "SFOAM", "modes": 2, "t_end": 3.0, "tip_mass": {"mass": 0.0, "position": 8.0},
            "maneuver": {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 0.5, "tf": 1.0},
                         "gains": {"theta": 300.0, "theta_dot": 90.0}}}
    pd = dict(case, maneuver={"kind": "pd", "kp": 300.0, "kd": 90.0, "reference": case["maneuver"]["reference"]})
    resolved = functools.partial(resolve, beam=params)
    shaped_feedback = simulate(case, params, numerics, resolve=lambda c, sm: resolved(c, sm)._replace(shaper=THREE))
    shaped_pd = simulate(pd, params, numerics, resolve=shaped(THREE))
    assert "three impulses" in shaped_feedback.attrs["shaper"]
    assert "shaper" not in simulate(pd, params, numerics).attrs
    # PD is state feedback on the hub angle and speed: the same shaped run
    np.testing.assert_allclose(shaped_feedback.hub_torque, shaped_pd.hub_torque, rtol=1e-12,
                               atol=1e-12 * float(np.abs(shaped_pd.hub_torque).max()))
