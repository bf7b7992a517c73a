"""Sampled designs for the rig: discrete LQR, the Kalman filter, the kernel's controllers, the export.

* discrete LQR tends to the continuous LQR as ``Ts -> 0``, at first order (halving ``Ts`` halves the
  gap); the continuous gain through the hold has the sampled loop's poles;
* the Kalman filter: ``L = Ad M``, ``P`` solves the filter's Riccati equation, and the a-priori and
  a-posteriori covariances match the sample covariances of the estimation errors over a long run of
  the plant driven by the design's noises (the batch-means standard error as the bound);
* every refusal, with the mode, its frequency and the sample time in its message;
* the controllers follow the kernel's convention; the design's loop has the poles the separation
  principle predicts; the filtered differences give a ramp's slope exactly;
* the export: controller and plant loaded back from ``.mat`` and ``.json`` close a loop with the
  design's poles to 1e-8.
"""

import dataclasses
import json
import math

import control as ct
import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from hubbeam.control.dlqr import continuous_lqr, discrete_lqr
from hubbeam.control.implementation import controller_system, read_implementation, write_implementation
from hubbeam.control.kalman import kalman_filter
from hubbeam.control.sampled import (
    closed_loop_matrix,
    filtered_difference_controller,
    kalman_controller,
    kernel_layout,
    rigid_feedforward,
    state_controller,
)
from hubbeam.control.sampling import measurement_rows, weight_matrix
from hubbeam.linear.discrete import discretise
from hubbeam.linear.lumped import QUANSER_ROTARY_FLEXIBLE_LINK as RIG
from hubbeam.linear.lumped import lumped_model
from hubbeam.linear.reduction import reduce_for_sampling
from hubbeam.linear.statespace import linear_model
from hubbeam.linear.voltage import voltage_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.drive import QUANSER_SRV02
from hubbeam.model.maneuvers import SensorSpec
from hubbeam.model.matrices import assemble

LAB_WEIGHTS = {"theta": 160.0, "alpha": 60.0, "theta_dot": 0.25, "alpha_dot": 1.0}
AXIAL_DAMPING = {"kind": "modal", "axial": 0.01, "transverse": 0.0}
ENCODER = 2 * np.pi / 4096  # rad per count
SENSORS = (SensorSpec("hub_angle", quantum=ENCODER), SensorSpec("deflection_angle", gain=1.0, noise=2e-3))


@pytest.fixture(scope="module")
def lumped():
    return lumped_model()


@pytest.fixture(scope="module")
def simulated():
    """The simulated model: FOAM with 5 modes on the Quanser link, its free-hub voltage model."""
    beam = RIG.beam()
    sm = assemble(beam, None, 5)
    return voltage_model(beam, sm, "FOAM", QUANSER_SRV02, 0.0, damping_matrices(AXIAL_DAMPING, sm))


def matched(poles, predicted):
    """The largest distance between two sets of poles, paired by an optimal assignment."""
    distance = np.abs(np.subtract.outer(np.asarray(poles), np.asarray(predicted)))
    rows, columns = linear_sum_assignment(distance)
    assert len(rows) == len(poles) == len(predicted)
    return float(distance[rows, columns].max())


# --- LQR ----------------------------------------------------------------------------------------------------


def test_discrete_lqr_tends_to_the_continuous_gain_at_first_order(lumped):
    """K_d(Ts) = K_c + O(Ts) and Ts P_d(Ts) = P_c + O(Ts): each halving of Ts halves the gaps (ratio
    within 5 % of 2 from Ts = 2.5 ms down; measured 1.97 and 1.99)."""
    Kc, Pc, _ = ct.lqr(lumped.A, lumped.B, weight_matrix(lumped, LAB_WEIGHTS), 1.0)
    steps = (0.0025, 0.00125, 0.000625)
    designs = [discrete_lqr(discretise(lumped, Ts), LAB_WEIGHTS, 1.0) for Ts in steps]
    gaps = [np.abs(d.K - np.asarray(Kc)[0]).max() for d in designs]
    riccati = [np.abs(d.P * Ts - Pc).max() for d, Ts in zip(designs, steps)]
    for series in (gaps, riccati):
        for coarse, fine in zip(series[:-1], series[1:]):
            assert coarse / fine == pytest.approx(2.0, rel=0.05)
    assert gaps[-1] < 0.03 * np.abs(Kc).max()


def test_the_continuous_gain_through_the_hold(lumped):
    dm = discretise(lumped, 0.002, 1.5)
    design = continuous_lqr(dm, LAB_WEIGHTS, 1.0)
    Kc = ct.lqr(lumped.A, lumped.B, weight_matrix(lumped, LAB_WEIGHTS), 1.0)[0][0]
    np.testing.assert_array_equal(design.K[:4], Kc)
    np.testing.assert_array_equal(design.K[4:], [0.0, 0.0])
    assert matched(design.poles, np.linalg.eigvals(dm.A - np.outer(dm.B[:, 0], design.K))) == 0.0
    assert np.abs(design.poles).max() < 1.0
    # a delayed design may weight the delayed commands too
    delayed = discrete_lqr(dm, LAB_WEIGHTS | {"voltage_lag1": 0.1}, 1.0)
    assert delayed.K.shape == (6,) and np.abs(delayed.poles).max() < 1.0


def test_lqr_refusals(lumped):
    dm = discretise(lumped, 0.002)
    with pytest.raises(ValueError, match="input_weight = 0; allowed: a finite weight > 0"):
        discrete_lqr(dm, LAB_WEIGHTS, 0)
    with pytest.raises(ValueError, match="weights.gamma: unknown name; allowed: the states theta, alpha"):
        discrete_lqr(dm, {"gamma": 1.0}, 1.0)
    with pytest.raises(ValueError, match=r"weights.alpha = -1.0; allowed: weights >= 0"):
        discrete_lqr(dm, {"alpha": -1.0}, 1.0)
    with pytest.raises(ValueError, match=r"leaves the rigid-body mode \(0 Hz, mostly theta\) at z = 1\+0j "
                                         r"\(Ts = 0.002 s\), not asymptotically stable"):
        discrete_lqr(dm, {"alpha": 1.0}, 1.0)
    beam = RIG.beam()
    undamped = linear_model(beam, assemble(beam, None, 1), "FOAM", 0.0)  # the axial mode: no damping, no torque
    with pytest.raises(ValueError, match=r"vibration mode 2 \(3011.\d+ Hz, mostly q1_1\) \(z = .*, not asymptotically "
                                         r"stable, Ts = 0.0001 s\) is left undisturbed by the input"):
        discrete_lqr(discretise(undamped, 1e-4), {"theta": 1.0}, 1.0)


# --- the Kalman filter --------------------------------------------------------------------------------------


def test_the_filter_gains_and_its_riccati_equation(lumped):
    dm = discretise(lumped, 0.005, 0.5)
    kf = kalman_filter(dm, SENSORS, input_noise=0.5, state_noise={"alpha": 1e-6})
    np.testing.assert_allclose(kf.L, dm.A @ kf.M, rtol=0.0, atol=1e-13 * np.abs(kf.L).max())
    A, C, P = dm.A, kf.Cm, kf.P
    S = C @ P @ C.T + kf.Rv
    residual = A @ P @ A.T + kf.G @ kf.Qw @ kf.G.T - A @ P @ C.T @ np.linalg.solve(S, C @ P @ A.T) - P
    assert np.abs(residual).max() <= 1e-9 * np.abs(P).max()
    np.testing.assert_allclose(kf.P_posterior, P - kf.M @ S @ kf.M.T, rtol=0.0, atol=1e-12 * np.abs(P).max())
    assert np.abs(kf.poles).max() < 1.0
    # the delayed command is known: the filter is sure of it
    assert kf.P[-1, -1] == pytest.approx(0.0, abs=1e-12 * np.abs(P).max())
    assert kf.Rv[0, 0] == pytest.approx(ENCODER**2 / 12, rel=1e-15)


def test_the_covariances_are_those_of_the_estimation_errors(lumped):
    """A run of 120 000 samples of the discrete plant driven by the design's process noise and
    measured with its noise; the errors x - xbar (a priori, predictor) and x - xhat (a posteriori,
    current estimate) after 2 000 samples of settling, cut into 40 batches of 2 950 (the errors'
    correlation decays within a few hundred samples: the slowest filter pole has |z| = 0.981). Each
    entry of the mean of the batch second moments against P and (I - M C) P: within 4.5 of its
    batch-means standard error (Student t with 39 degrees of freedom: 1e-4 per entry; measured at
    most 2.6, the standard errors 0.5 to 2 % of the entries). The wrong covariance, the a-posteriori
    one for the a-priori errors, is refused by the same bound (measured 186)."""
    dm = discretise(lumped, 0.005)
    kf = kalman_filter(dm, SENSORS, input_noise=0.5, state_noise={"alpha": 1e-6})
    rng = np.random.default_rng(20240611)
    steps, settle, batches = 120_000, 2_000, 40
    w = rng.standard_normal((steps, kf.Qw.shape[0])) * np.sqrt(np.diag(kf.Qw))
    v = rng.standard_normal((steps, len(SENSORS))) * np.sqrt(np.diag(kf.Rv))
    x = np.zeros(4)
    xbar = np.zeros(4)
    prior, posterior = np.empty((steps, 4)), np.empty((steps, 4))
    A, G, C, M = dm.A, kf.G, kf.Cm, kf.M
    for k in range(steps):
        m = C @ x + v[k]
        xhat = xbar + M @ (m - C @ xbar)
        prior[k], posterior[k] = x - xbar, x - xhat
        x = A @ x + G @ w[k]
        xbar = A @ xhat

    def scores(errors, expected):
        chunks = np.array_split(errors[settle:], batches)
        moments = np.array([chunk.T @ chunk / len(chunk) for chunk in chunks])
        error = moments.std(axis=0, ddof=1) / math.sqrt(batches)
        upper = np.triu_indices(4)
        return np.abs((moments.mean(axis=0) - expected)[upper] / error[upper])

    assert scores(prior, kf.P).max() < 4.5
    assert scores(posterior, kf.P_posterior).max() < 4.5
    assert scores(prior, kf.P_posterior).max() > 4.5


def test_kalman_refusals(lumped, simulated):
    beam = RIG.beam()
    sm = assemble(beam, None, 5)
    foam = voltage_model(beam, sm, "FOAM", QUANSER_SRV02, 0.0, damping_matrices(AXIAL_DAMPING, sm))
    with pytest.raises(ValueError, match=r"vibration mode 3 \(61.\d+ Hz, mostly \w+\) of FOAM_free_hub_0rad_s_voltage "
                                         r"lies above half the sampling frequency 25 Hz \(Ts = 0.02 s\)"):
        kalman_filter(discretise(foam, 0.02), SENSORS, input_noise=1.0)
    reduced, error = reduce_for_sampling(foam, 0.02)
    kalman_filter(discretise(reduced, 0.02), SENSORS, input_noise=1.0)  # the reduced model is accepted
    with pytest.raises(ValueError, match=r"the rigid-body mode \(0 Hz, mostly theta\) \(z = 1\+0j, Ts = 0.002 s\) is "
                                         "undetectable from the measured signals"):
        kalman_filter(discretise(lumped, 0.002), SENSORS[1:], input_noise=1.0)
    # the flexible mode sampled at exactly half the sampling frequency: its two poles sample to one
    # real z, which the hub angle alone cannot tell apart (the two signals can)
    wd = np.abs(np.linalg.eigvals(lumped.A).imag).max()
    at_nyquist = discretise(lumped, math.pi / wd)
    with pytest.raises(ValueError, match=r"vibration mode 1 \(3.75\d+ Hz, mostly alpha\) is lost by pathological "
                                         r"sampling: .* Ts = 0.133\d+ s \(a mode at half the sampling frequency "
                                         r"3.75\d+ Hz\)"):
        kalman_filter(at_nyquist, SENSORS[:1], input_noise=1.0)
    kalman_filter(at_nyquist, SENSORS, input_noise=1.0)
    with pytest.raises(ValueError, match=r"the rigid-body mode \(0 Hz, mostly theta\) \(z = 1\+0j, on the unit circle, "
                                         r"Ts = 0.002 s\) is left undisturbed by the process noise"):
        kalman_filter(discretise(lumped, 0.002), SENSORS, state_noise={"alpha": 1.0})
    # with a torque input and no drive the rigid-body pair is a double z = 1: noise on the angle alone
    # leaves its momentum undisturbed
    bending = linear_model(beam, assemble(beam, None, 2), "SFOAM", 0.0)
    with pytest.raises(ValueError, match=r"the rigid-body mode \(0 Hz, mostly theta\) .* on the unit circle, "
                                         r"Ts = 0.002 s\) is left undisturbed by the process noise"):
        kalman_filter(discretise(bending, 0.002), SENSORS, state_noise={"theta": 1.0})
    dm = discretise(lumped, 0.002)
    with pytest.raises(ValueError, match=r"sensors\[0\] \(hub_angle\): noise variance .* = 0.0; allowed: > 0"):
        kalman_filter(dm, [SensorSpec("hub_angle")], input_noise=1.0)
    with pytest.raises(ValueError, match="measurement_covariance has the eigenvalue -1; allowed: a positive definite"):
        kalman_filter(dm, SENSORS, input_noise=1.0, measurement_covariance=[[1.0, 2.0], [2.0, 1.0]])
    with pytest.raises(ValueError, match=r"input_noise = -1.0; allowed: a variance >= 0"):
        kalman_filter(dm, SENSORS, input_noise=-1.0)
    with pytest.raises(ValueError, match=r"state_noise.alpha = -1.0; allowed: a variance >= 0"):
        kalman_filter(dm, SENSORS, input_noise=1.0, state_noise={"alpha": -1.0})
    with pytest.raises(ValueError, match=r"state_noise.q2_1: unknown name; allowed: the plant's states theta, alpha"):
        kalman_filter(dm, SENSORS, input_noise=1.0, state_noise={"q2_1": 1.0})
    with pytest.raises(ValueError, match=r"sensors\[1\].signal = 'tip_acceleration' has a feedthrough from the input"):
        measurement_rows(simulated, [SensorSpec("hub_angle"), SensorSpec("tip_acceleration")])
    with pytest.raises(ValueError, match=r"sensors\[0\].signal = 'encoder': not an output of"):
        kalman_filter(dm, [SensorSpec("encoder", noise=1.0)], input_noise=1.0)
    with pytest.raises(ValueError, match=r"sensors\[0\].gain = 0.0; allowed: a finite, non-zero number"):
        kalman_filter(dm, [SensorSpec("hub_angle", gain=0.0, noise=1.0)], input_noise=1.0)


# --- the controllers ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("form", ["current", "predictor"])
def test_the_kalman_controller_in_the_kernels_convention(lumped, simulated, form):
    dm = discretise(lumped, 0.002, 0.5)
    kf = kalman_filter(dm, SENSORS, input_noise=0.5, form=form)
    lqr = discrete_lqr(dm, LAB_WEIGHTS, 1.0)
    c = kalman_controller(lqr, kf, simulated, u_max=10.0, u_init=0.25)
    I = np.eye(5)
    if form == "predictor":
        expected = {"E": I, "F": np.zeros((5, 2)), "Ac": dm.A - kf.L @ kf.Cm, "Bc": kf.L}
    else:
        expected = {"E": I - kf.M @ kf.Cm, "F": kf.M, "Ac": dm.A @ (I - kf.M @ kf.Cm), "Bc": dm.A @ kf.M}
    for name, value in expected.items():
        np.testing.assert_array_equal(getattr(c, name), value)
    np.testing.assert_array_equal(c.Bu, dm.B[:, 0])
    np.testing.assert_array_equal(c.xc0, [0.0, 0.0, 0.0, 0.0, 0.25])
    assert (c.Ts, c.D, c.u_max, c.u_init) == (0.002, 0.5, 10.0, 0.25)
    # the sensors read the simulated FOAM's rows on the kernel's state (theta, q1, q2 and rates)
    layout = kernel_layout(simulated)
    assert c.sensor_rows.shape == (2, len(layout)) and c.sensor_rows[0, 0] == 1.0
    np.testing.assert_array_equal(c.sensor_rows[1, [layout.index(s) for s in simulated.states]],
                                  simulated.C[simulated.outputs.index("deflection_angle")])
    np.testing.assert_array_equal(c.R_m, [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    # the design's loop: the separation principle's poles, eig(Ad - Bd K) and eig(Ad - L C)
    loop = np.linalg.eigvals(closed_loop_matrix(dm, kf.Cm, c.Ac, c.Bc, c.Bu, c.E, c.F, c.K))
    assert matched(loop, c.poles) < 1e-9


def test_the_true_state_controller_reads_the_design_states_on_the_simulated_model(lumped, simulated):
    dm = discretise(lumped, 0.002, 1.5)
    lqr = discrete_lqr(dm, LAB_WEIGHTS, 1.0)
    c = state_controller(lqr, simulated, u_init=0.5)
    assert [s.signal for s in c.sensors] == ["theta", "deflection_angle", "theta_dot", "deflection_rate"]
    assert c.controller_states == ("voltage_lag1", "voltage_lag2")
    np.testing.assert_array_equal(c.Ac, [[0.0, 0.0], [1.0, 0.0]])
    np.testing.assert_array_equal(c.Bu, [1.0, 0.0])
    np.testing.assert_array_equal(c.xc0, [0.5, 0.5])
    np.testing.assert_array_equal(c.R_m, [[1, 0, 0], [0, 0, 0], [0, 1, 0], [0, 0, 0]])
    # the loop's poles: the design's and, at 0, the plant's delayed command less the controller's copy;
    # with one delayed command 0 is a double pole (the design's own one too), which rounding splits by
    # up to about sqrt(eps) (measured 8e-11); the others agree to rounding
    half = discretise(lumped, 0.002, 0.5)
    one = state_controller(discrete_lqr(half, LAB_WEIGHTS, 1.0), simulated)
    loop = np.linalg.eigvals(closed_loop_matrix(half, np.eye(5)[:4], one.Ac, one.Bc, one.Bu, one.E, one.F, one.K))
    assert matched(loop, one.poles) < math.sqrt(np.finfo(float).eps)
    assert matched(loop[np.abs(loop) > 1e-6], one.poles[np.abs(one.poles) > 1e-6]) < 1e-12
    # a FOAM design read on a FOAM with more modes: its own states, q1 slots of the layout included
    beam = RIG.beam()
    sm = assemble(beam, None, 2)
    design = discrete_lqr(discretise(voltage_model(beam, sm, "SFOAM", QUANSER_SRV02), 0.002),
                          {"hub_angle": 160.0, "deflection_angle": 60.0, "hub_speed": 0.25, "deflection_rate": 1.0},
                          1.0)
    foam = state_controller(design, simulated)
    layout = kernel_layout(simulated)
    assert [layout[int(np.argmax(row))] for row in foam.sensor_rows] == list(design.model.states)
    with pytest.raises(ValueError, match="u_max = 0; allowed: a command limit > 0"):
        state_controller(lqr, simulated, u_max=0)


def test_the_filtered_differences_follow_a_ramp(lumped, simulated):
    dm = discretise(lumped, 0.002)
    lqr = discrete_lqr(dm, LAB_WEIGHTS, 1.0)
    sensors = (SensorSpec("hub_angle", quantum=ENCODER), SensorSpec("deflection_angle", gain=0.5))
    c = filtered_difference_controller(lqr, sensors, 2 * np.pi * 50, simulated)
    np.testing.assert_array_equal(c.K, lqr.K)
    assert c.estimate_states == ("hub_angle", "deflection_angle", "hub_speed", "deflection_rate")
    xc = c.xc0.copy()
    slope = np.array([0.7, -0.3])  # rad/s of the signals; the deflection sensor reads half of it
    for k in range(400):
        e = np.array([1.0, 0.5]) * slope * k * 0.002
        xhat = c.E @ xc + c.F @ e
        xc = c.Ac @ xc + c.Bc @ e
    np.testing.assert_allclose(xhat, [slope[0] * 399 * 0.002, slope[1] * 399 * 0.002, *slope], rtol=1e-12)
    Cm = np.array([[1.0, 0, 0, 0], [0, 0.5, 0, 0]])
    loop = np.linalg.eigvals(closed_loop_matrix(dm, Cm, c.Ac, c.Bc, c.Bu, c.E, c.F, c.K))
    assert matched(loop, c.poles) < 1e-12 and np.abs(c.poles).max() < 1.0
    with pytest.raises(ValueError, match="has no state that is the signal 'deflection_angle'"):
        beam = RIG.beam()
        foam = discretise(voltage_model(beam, assemble(beam, None, 1), "SFOAM", QUANSER_SRV02), 0.002)
        filtered_difference_controller(discrete_lqr(foam, {"theta": 1.0}, 1.0), sensors, 100.0, simulated)


def test_the_rigid_feedforward():
    U = rigid_feedforward(0.006, QUANSER_SRV02)
    # on the rigid body, tau = kV V - c theta' = J theta'' for V = U . rho
    rho = np.array([0.3, 1.2, -4.0])
    assert QUANSER_SRV02.torque_gain * (U @ rho) - QUANSER_SRV02.hub_damping * rho[1] == pytest.approx(0.006 * rho[2])
    np.testing.assert_array_equal(rigid_feedforward(2.0), [0.0, 0.0, 2.0])


# --- the export ---------------------------------------------------------------------------------------------


def controllers(lumped, simulated):
    out = []
    for delay in (0.0, 0.5):
        dm = discretise(lumped, 0.002, delay)
        lqr = discrete_lqr(dm, LAB_WEIGHTS, 1.0)
        for form in ("current", "predictor"):
            out.append(kalman_controller(lqr, kalman_filter(dm, SENSORS, input_noise=0.5, form=form), simulated,
                                         u_max=10.0, feedforward=rigid_feedforward(0.006, QUANSER_SRV02)))
        out.append(state_controller(lqr, simulated))
    dm = discretise(lumped, 0.002)
    out.append(filtered_difference_controller(discrete_lqr(dm, LAB_WEIGHTS, 1.0), SENSORS, 300.0, simulated))
    return out


def test_the_exported_controller_and_plant_close_the_designed_loop(lumped, simulated, tmp_path):
    for k, controller in enumerate(controllers(lumped, simulated)):
        paths = write_implementation(controller, tmp_path / f"controller{k}")
        for path in paths:
            K, P = read_implementation(path)
            assert K.dt == P.dt == 0.002
            signals = [sensor.signal for sensor in controller.sensors]
            assert K.input_labels == signals + ["reference_angle", "reference_speed", "reference_acceleration"]
            assert P.output_labels == signals and K.output_labels == ["voltage"] == P.input_labels
            loop = ct.feedback(P, K[:, list(range(len(signals)))], sign=1)
            # the design's loop to 1e-8 of the largest pole (|z| <= 1); the poles are simple (at most
            # one delayed command), so rounding moves them by about eps times their condition
            assert matched(ct.poles(loop), controller.poles) < 1e-8, (controller.kind, path.suffix)
    document = json.loads(paths[1].read_text())
    assert document["sensors"][0] == {"signal": "hub_angle", "gain": 1.0, "unit": "rad", "sigma": 0.0,
                                      "quantum": ENCODER}
    assert document["controller"]["output_units"] == ["V"]


def test_the_reference_path_of_the_exported_controller(lumped, simulated):
    """With the plant at the reference (m = R_m rho) and the controller at rest, the command is the
    feedforward U_r . rho: the reference path subtracts what the sensors read of the reference."""
    dm = discretise(lumped, 0.002)
    lqr = discrete_lqr(dm, LAB_WEIGHTS, 1.0)
    c = kalman_controller(lqr, kalman_filter(dm, SENSORS, input_noise=0.5), simulated,
                          feedforward=rigid_feedforward(0.006, QUANSER_SRV02))
    K = controller_system(c)
    rho = np.array([0.4, 0.9, 2.0])
    u = K.D @ np.concatenate([c.R_m @ rho, rho])
    assert u[0] == pytest.approx(c.U_r @ rho, rel=1e-12)
    np.testing.assert_allclose(K.B @ np.concatenate([c.R_m @ rho, rho]), 0.0, atol=1e-12)
    assert dataclasses.is_dataclass(c)
