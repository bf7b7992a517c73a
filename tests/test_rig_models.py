"""The rig's linear models: outputs, the drive's voltage input, the lumped model, sampling, reduction.

* the output rows are a table of named builders: an unknown name is refused; the link deflection
  angle is ``v(L) / L`` and its rate is the angle's row times ``A`` (a second route);
* the voltage model: ``B_V = kV B_tau``, the hub row damped by the drive, the steady speed under a
  constant voltage ``kV V / c`` (closed form), the regularised Coulomb friction's slope and the
  operating-point voltage against the drive's own torque law, ``R_V = kV^2 R_tau``;
* the Quanser lumped model against the courseware's matrices (``setup_flexlink_exp.m``) and its
  LQR with the lab's weights; the same weights on FOAM with one and with more modes;
* the zero-order hold with a delay against python-control's ``sample_system`` (no delay) and
  against a numerical integration of the delayed staircase (whole and fractional delays);
* the discrete and voltage models through the export files;
* modal truncation: the kept poles exactly, the full model back when nothing is dropped, the
  error falling as modes are kept;
* light-hub mode names: every free-hub bending mode named apart.
"""

import dataclasses
import math

import control as ct
import numpy as np
import pytest
import scipy.linalg
from scipy.integrate import solve_ivp
from scipy.io import loadmat

from hubbeam.control.sampling import weight_matrix
from hubbeam.linear import datasets, tracking
from hubbeam.linear.axes import tip_mass_axis
from hubbeam.linear.discrete import discretise, hold_matrices
from hubbeam.linear.export import to_dataset, write_dataset, write_mat
from hubbeam.linear.lumped import QUANSER_ROTARY_FLEXIBLE_LINK as RIG
from hubbeam.linear.lumped import FlexibleLinkRig, lumped_model
from hubbeam.linear.reduction import frequency_responses, modal_truncation, reduce_for_sampling, response_error
from hubbeam.linear.statespace import linear_model, output_rows, second_order
from hubbeam.linear.voltage import linearised_damping, voltage_model, voltage_weight
from hubbeam.model.damping import damping_from_dict, damping_matrices
from hubbeam.model.drive import QUANSER_SRV02, DcMotor
from hubbeam.model.matrices import assemble
from hubbeam.model.models import model as model_traits
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.plant import Plant
from hubbeam.results.io import open_result

EPS = np.finfo(float).eps
#: the lab's LQR weights on (theta, alpha, theta', alpha') and on volts^2 (setup_flexlink_exp.m)
LAB_WEIGHTS = {"theta": 160.0, "alpha": 60.0, "theta_dot": 0.25, "alpha_dot": 1.0}
#: the same weights on the assumed-modes models' outputs
LAB_OUTPUT_WEIGHTS = {"hub_angle": 160.0, "deflection_angle": 60.0, "hub_speed": 0.25, "deflection_rate": 1.0}
#: the axial modes of FOAM at rest are neither moved by the torque nor weighted; a little damping
#: keeps them stable, so that the Riccati equations are solvable (the bending modes stay undamped)
AXIAL_DAMPING = {"kind": "modal", "axial": 0.01, "transverse": 0.0}


@pytest.fixture(scope="module")
def link():
    return RIG.beam()


def foam(link, n, damping=AXIAL_DAMPING):
    sm = assemble(link, None, n)
    return sm, damping_matrices(damping, sm)


# --- outputs ------------------------------------------------------------------------------------------


def test_an_unknown_output_name_is_refused_by_the_row_table(link):
    sm = assemble(link, None, 2)
    traits = model_traits("FOAM").traits
    with pytest.raises(ValueError, match="'tip_speed' is unknown; allowed: names among hub_angle"):
        output_rows(link, sm, traits, 0.0, np.zeros(2), ["hub_angle", "tip_speed"])


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "SFOAM", "CFOAM"])
def test_the_deflection_angle_is_the_tip_deflection_over_the_length_and_its_rate_its_derivative(link, model):
    sm, C = foam(link, 4)
    lm = linear_model(link, sm, model, 1.5, "free", C, outputs=["tip_deflection", "deflection_angle",
                                                                 "deflection_rate"])
    tip, angle, rate = lm.C
    np.testing.assert_allclose(angle, tip / link.L, rtol=1e-15, atol=0.0)
    # d/dt (c x) = c A x + c B u: the angle's row has no input path, so its rate's row is c A
    assert np.all(angle @ lm.B == 0.0)
    np.testing.assert_allclose(rate, angle @ lm.A, rtol=0.0, atol=1e-14 * np.abs(angle @ lm.A).max())


# --- the voltage model ---------------------------------------------------------------------------------


def test_the_voltage_model_is_the_torque_model_with_the_drive_on_the_hub_row(link):
    sm, C = foam(link, 3)
    torque = linear_model(link, sm, "FOAM", 0.0, "free", C)
    volts = voltage_model(link, sm, "FOAM", QUANSER_SRV02, 0.0, C)
    kV, c = QUANSER_SRV02.torque_gain, QUANSER_SRV02.hub_damping
    assert volts.inputs == ("voltage",) and volts.operating_voltage == 0.0 and volts.hub_damping == c
    np.testing.assert_allclose(volts.B, kV * torque.B, rtol=1e-13, atol=0.0)
    # the drive adds -c theta' to the hub's generalised force: A changes by -c B_tau in theta_dot's column
    change = np.zeros_like(torque.A)
    change[:, torque.states.index("theta_dot")] = -c * torque.B[:, 0]
    np.testing.assert_allclose(volts.A - torque.A, change, rtol=0.0, atol=1e-12 * np.abs(torque.A).max())


def test_a_constant_voltage_turns_the_hub_at_gain_times_voltage_over_damping(link):
    """Steady state of the linear model under V: the angle grows at a constant speed s with every
    other state constant, A x + B V = s e_theta; the closed form is s = kV V / c (the drive's torque
    kV (V - Kg km s) - B s vanishes)."""
    sm, C = foam(link, 3)
    lm = voltage_model(link, sm, "FOAM", QUANSER_SRV02, 0.0, C)
    V = 2.5
    n = lm.A.shape[0]
    theta = lm.states.index("theta")
    # unknowns: x without theta (cyclic, set to 0) and s
    columns = [k for k in range(n) if k != theta]
    system = np.hstack([lm.A[:, columns], -np.eye(n)[:, [theta]]])
    solution = np.linalg.solve(system, -lm.B[:, 0] * V)
    speed = solution[-1]
    assert speed == pytest.approx(QUANSER_SRV02.torque_gain * V / QUANSER_SRV02.hub_damping, rel=1e-12)
    assert float(QUANSER_SRV02.torque(V, speed)) == pytest.approx(0.0, abs=1e-14)
    x = np.insert(solution[:-1], theta, 0.0)
    assert x[lm.states.index("theta_dot")] == pytest.approx(speed, rel=1e-12)


def test_the_coulomb_friction_is_linearised_about_the_operating_speed(link):
    motor = dataclasses.replace(QUANSER_SRV02, coulomb_friction=0.02, coulomb_smoothing=0.05)
    sm, C = foam(link, 2)
    for speed in (0.0, 0.04, 1.0):
        lm = voltage_model(link, sm, "FOAM", motor, speed, C)
        # the steady spin needs V0: the drive's torque there is zero
        assert float(motor.torque(lm.operating_voltage, speed)) == pytest.approx(0.0, abs=1e-15)
        # minus the slope of the drive's torque with the speed, by a central difference: truncation
        # h^2 Fc / eps^3 / 6 = 3e-11, rounding eps_machine |tau| / h ~ 1e-11, against c ~ 0.1..0.5
        h = 1e-6
        volts = lm.operating_voltage
        slope = (motor.torque(volts, speed + h) - motor.torque(volts, speed - h)) / (2 * h)
        assert lm.hub_damping == pytest.approx(-slope, rel=1e-9)
        assert lm.hub_damping == pytest.approx(linearised_damping(motor, speed), rel=1e-15)
    # about rest the regularised friction is a damper Fc / eps on top of back-EMF and viscous friction
    assert linearised_damping(motor, 0.0) == pytest.approx(motor.hub_damping + 0.02 / 0.05, rel=1e-15)


def test_a_speed_beyond_the_amplifier_is_refused(link):
    sm, C = foam(link, 2)
    too_fast = 1.01 * QUANSER_SRV02.torque_gain * QUANSER_SRV02.voltage_limit / QUANSER_SRV02.hub_damping
    with pytest.raises(ValueError, match="beyond the amplifier's limit 10 V"):
        voltage_model(link, sm, "FOAM", QUANSER_SRV02, too_fast, C)
    with pytest.raises(ValueError, match="motor = 'SRV02'; allowed: a hubbeam.model.drive.DcMotor"):
        voltage_model(link, sm, "FOAM", "SRV02", 0.0, C)


def test_a_torque_weight_becomes_gain_squared_times_it_on_volts(link):
    """The same cost: LQR on volts with R_V = kV^2 R_tau gives the torque gain kV K_V of the LQR on
    the commanded torque kV u of the same (drive-damped) plant."""
    sm, C = foam(link, 2)
    lm = voltage_model(link, sm, "FOAM", QUANSER_SRV02, 0.0, C, outputs=list(LAB_OUTPUT_WEIGHTS))
    Q = weight_matrix(lm, LAB_OUTPUT_WEIGHTS)
    kV = QUANSER_SRV02.torque_gain
    K_volts = ct.lqr(lm.A, lm.B, Q, voltage_weight(0.3, QUANSER_SRV02))[0]
    K_torque = ct.lqr(lm.A, lm.B / kV, Q, 0.3)[0]
    # two Riccati solutions, each to about 1e-10 of the largest gain (the axial gains are ~1e-10)
    np.testing.assert_allclose(kV * K_volts, K_torque, rtol=1e-8, atol=1e-9 * np.abs(K_torque).max())


# --- the Quanser lumped model ----------------------------------------------------------------------------


def courseware_matrices(rig):
    """A and B as the Quanser courseware's setup_flexlink_exp.m writes them (Rotary Flexible Link,
    script "SETUP_FLEXLINK_EXP"; K_Stiff = w_r^2 Jl from config_flexgage_exp.m, Jeq with the clamp's
    Jload = 0.0002 from config_servo_exp.m), transcribed:

        beta_m = eta_m*eta_g*kt*Kg/Rm;
        A = [zeros(2) eye(2);
             0, K_Stiff/Jeq, -(Beq + beta_m*km*Kg)/Jeq, 0;
             0, -K_Stiff*(Jeq + Jl)/(Jeq*Jl), (Beq + beta_m*km*Kg)/Jeq, 0];
        B = beta_m/Jeq*[zeros(2,1); 1; -1];
    """
    m = rig.motor
    beta_m = m.motor_efficiency * m.gearbox_efficiency * m.torque_constant * m.gear_ratio / m.resistance
    Jeq, Jl, Beq = rig.hub, rig.link_mass * rig.length**2 / 3, m.viscous_friction
    Ks = (2 * np.pi * 3) ** 2 * Jl
    damp = Beq + beta_m * m.back_emf_constant * m.gear_ratio
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [np.array([[0.0, Ks / Jeq, -damp / Jeq, 0.0],
                             [0.0, -Ks * (Jeq + Jl) / (Jeq * Jl), damp / Jeq, 0.0]])]])
    B = beta_m / Jeq * np.array([[0.0], [0.0], [1.0], [-1.0]])
    return A, B


def test_the_lumped_model_is_the_courseware_model():
    """Our route (the mass matrix of the rod on a torsion spring, inverted) against the courseware's
    closed-form matrices: the same to rounding. The Quanser courseware's own published gain vector
    for these weights was not found in a public copy; the gains are checked against a second
    Riccati solver on the courseware's matrices and against the closed form of the hub-angle gain."""
    lm = lumped_model()
    A, B = courseware_matrices(RIG)
    np.testing.assert_allclose(lm.A, A, rtol=1e-13, atol=1e-13 * np.abs(A).max())
    np.testing.assert_allclose(lm.B, B, rtol=1e-13, atol=0.0)
    Q = np.diag(list(LAB_WEIGHTS.values()))
    K = ct.lqr(lm.A, lm.B, weight_matrix(lm, LAB_WEIGHTS), 1.0)[0][0]
    P = scipy.linalg.solve_continuous_are(A, B, Q, np.eye(1))
    np.testing.assert_allclose(K, (B.T @ P)[0], rtol=1e-9)
    # the hub angle is cyclic (a zero column of A): the (theta, theta) entry of the Riccati equation
    # reads (B^T P)_theta^2 / R = Q_theta, so K_theta = sqrt(160 / 1) whatever the rest
    assert K[0] == pytest.approx(math.sqrt(160.0), rel=1e-10)


def test_the_lumped_frequencies_are_the_fitted_three_hertz_and_the_free_hub_formula():
    lm = lumped_model()
    # hub held: J_l alpha'' + Ks alpha = 0
    assert math.sqrt(RIG.spring_stiffness / RIG.link_inertia) / (2 * np.pi) == pytest.approx(3.0, rel=1e-15)
    # hub free without the drive's damping: the undamped pair at f sqrt((Jeq + Jl) / Jeq)
    idle = dataclasses.replace(RIG, motor=DcMotor(resistance=2.6, torque_constant=7.68e-3, back_emf_constant=0.0))
    free = np.abs(np.linalg.eigvals(lumped_model(idle).A).imag).max() / (2 * np.pi)
    assert free == pytest.approx(RIG.free_frequency, rel=1e-12)
    assert RIG.free_frequency == pytest.approx(3.0 * math.sqrt((0.00228 + 0.065 * 0.419**2 / 3) / 0.00228), rel=1e-15)
    assert lm.outputs[:2] == ("hub_angle", "deflection_angle")
    with pytest.raises(ValueError, match="length = -1.0; allowed: a finite number > 0"):
        FlexibleLinkRig(**(dataclasses.asdict(RIG) | {"length": -1.0, "motor": QUANSER_SRV02}))


@pytest.mark.parametrize("n", [1, 5])
def test_the_lab_weights_on_foam(link, n):
    """The lab's LQR on FOAM with the Quanser link: the closed form of the hub-angle gain holds, and
    the gains converge in the modes (5 against 10: 1e-3 relative; measured 1.2e-4 on the deflection
    gains)."""
    sm, C = foam(link, n)
    lm = voltage_model(link, sm, "FOAM", QUANSER_SRV02, 0.0, C, outputs=list(LAB_OUTPUT_WEIGHTS))
    K = ct.lqr(lm.A, lm.B, weight_matrix(lm, LAB_OUTPUT_WEIGHTS), 1.0)[0][0]
    assert K[lm.states.index("theta")] == pytest.approx(math.sqrt(160.0), rel=1e-9)
    if n > 1:
        sm10, C10 = foam(link, 10)
        more = voltage_model(link, sm10, "FOAM", QUANSER_SRV02, 0.0, C10, outputs=list(LAB_OUTPUT_WEIGHTS))
        K10 = ct.lqr(more.A, more.B, weight_matrix(more, LAB_OUTPUT_WEIGHTS), 1.0)[0][0]
        for name in ("theta", "q2_1", "theta_dot", "q2_1_dot"):
            assert K[lm.states.index(name)] == pytest.approx(K10[more.states.index(name)], rel=1e-3)


# --- sampling ---------------------------------------------------------------------------------------------


def test_without_delay_the_hold_is_python_controls_zoh():
    lm = lumped_model()
    dm = discretise(lm, 0.002)
    reference = ct.sample_system(lm.to_control(), 0.002, method="zoh")
    for ours, theirs in ((dm.A, reference.A), (dm.B, reference.B), (dm.C, reference.C), (dm.D, reference.D)):
        np.testing.assert_allclose(ours, theirs, rtol=1e-13, atol=1e-15)
    system = dm.to_control()
    assert system.dt == 0.002 and system.state_labels == list(lm.states) and system.input_labels == ["voltage"]


def test_a_fractional_delay_splits_the_hold_and_a_whole_one_adds_lags():
    lm = lumped_model()
    Ts = 0.01
    gamma = hold_matrices(lm.A, lm.B, Ts)[1]
    half = discretise(lm, Ts, 0.25)  # one lag: u_{k-1} until t_k + Ts/4, then u_k
    assert half.states[-1] == "voltage_lag1" and half.lags == 1
    np.testing.assert_allclose(half.B[:4] + half.A[:4, 4:], gamma, rtol=1e-12, atol=0.0)  # Gamma_0 + Gamma_1
    two = discretise(lm, Ts, 2.0)
    assert two.lags == 2 and np.all(two.B[:4] == 0.0) and np.all(two.A[:4, 4] == 0.0)
    np.testing.assert_allclose(two.A[:4, 5:6], gamma, rtol=1e-13)
    assert two.B[4, 0] == 1.0 and two.A[5, 4] == 1.0


@pytest.mark.parametrize("delay", [0.0, 0.3, 1.0, 1.7])
def test_the_delayed_hold_matches_the_integrated_staircase(delay):
    """The samples of the discrete model against solve_ivp (DOP853, rtol 1e-12) of the continuous
    model fed the staircase u(t) = u_k on [t_k + D Ts, t_{k+1} + D Ts) (u_init = 0 before), each
    piece integrated separately: agreement to 1e-9 of the largest state (the integrator's
    tolerance)."""
    lm = lumped_model()
    Ts, steps = 0.02, 40
    u = np.sin(0.7 * np.arange(steps)) + 0.5
    dm = discretise(lm, Ts, delay)
    x = np.zeros(dm.A.shape[0])
    sampled = []
    for k in range(steps):
        sampled.append(x[:4].copy())
        x = dm.A @ x + dm.B[:, 0] * u[k]
    switches = [(k + delay) * Ts for k in range(steps)]
    y, t = np.zeros(4), 0.0
    integrated = [y.copy()]
    for k in range(1, steps):
        marks = sorted({t} | {s for s in switches if t < s < k * Ts} | {k * Ts})
        for a, b in zip(marks[:-1], marks[1:]):
            active = [j for j, s in enumerate(switches) if s <= a + 1e-15]
            level = u[active[-1]] if active else 0.0
            y = solve_ivp(lambda _, z, level=level: lm.A @ z + lm.B[:, 0] * level, (a, b), y, method="DOP853",
                          rtol=1e-12, atol=1e-14).y[:, -1]
        t = k * Ts
        integrated.append(y.copy())
    sampled, integrated = np.array(sampled), np.array(integrated)
    np.testing.assert_allclose(sampled, integrated, rtol=0.0, atol=1e-9 * np.abs(integrated).max())


def test_discrete_voltage_models_through_the_export_files(link, tmp_path):
    sm, C = foam(link, 2)
    plant = Plant(beam=link, modes=2, quadrature_points=64, tip=TipMass(0.0, link.L), drive=QUANSER_SRV02,
                  damping=damping_from_dict(AXIAL_DAMPING))
    ds = to_dataset(plant, "FOAM", [0.0, 1.0], "free", outputs=["hub_angle", "deflection_angle"], sample_time=0.002,
                    delay=0.5)
    dm = discretise(voltage_model(link, sm, "FOAM", QUANSER_SRV02, 1.0, C, ["hub_angle", "deflection_angle"]),
                    0.002, 0.5)
    assert ds.attrs["sample_time_s"] == 0.002 and ds.attrs["input_delay_samples"] == 0.5
    assert list(ds.state.values) == list(dm.states) and ds.state_units.values[-1] == "V"
    assert ds.operating_voltage.values[1] == pytest.approx(QUANSER_SRV02.voltage(0.0, 1.0), rel=1e-15)
    write_dataset(ds, tmp_path / "d.nc")
    write_mat(ds, tmp_path / "d.mat")
    with open_result(tmp_path / "d.nc") as stored:
        np.testing.assert_array_equal(stored.A.values[1], dm.A)
        np.testing.assert_array_equal(stored.B.values[1], dm.B)
    mat = loadmat(tmp_path / "d.mat")
    np.testing.assert_array_equal(mat["A"][:, :, 1], dm.A)
    assert float(mat["sample_time_s"].squeeze()) == 0.002
    assert [str(s[0]) for s in mat["states"].ravel()][-1] == "voltage_lag1"
    # the growth rate of the sampled rigid mode: ln |z| / Ts = 0
    assert abs(ds.growth_rate.values[0]) < 1e-9
    with pytest.raises(ValueError, match="Ts = 0.0; allowed: a finite sample time > 0 s"):
        discretise(dm.continuous, 0.0)
    with pytest.raises(ValueError, match="delay = -1; allowed: a finite input delay >= 0 samples"):
        discretise(dm.continuous, 0.01, -1)


# --- reduction --------------------------------------------------------------------------------------------


def test_modal_truncation_keeps_the_kept_poles_and_the_rigid_mode(link):
    sm, C = foam(link, 6, {"kind": "modal", "axial": 0.01, "transverse": 0.01})
    lm = linear_model(link, sm, "FOAM", 0.0, "free", C)
    reduced = modal_truncation(lm, 100.0)
    full = np.linalg.eigvals(lm.A)
    kept = full[np.abs(full) <= 2 * np.pi * 100.0]
    ours = np.linalg.eigvals(reduced.A)
    assert ours.size == kept.size == 8  # the rigid pair and three bending modes
    for pole in kept:  # each to the rounding of its eigenvalue (1e-9 of the largest kept)
        assert np.min(np.abs(ours - pole)) <= 1e-9 * np.abs(kept).max()
    np.testing.assert_allclose(reduced.projection @ reduced.expansion, np.eye(8), atol=1e-10)
    # the rigid body: the hub angle's response far below the first mode is 1 / (J w^2), J = Jh + Jb
    w = 2 * np.pi * 0.01
    J = second_order(sm, model_traits("FOAM"), 0.0)[0][0, 0]
    G = frequency_responses(reduced, np.array([w]))[reduced.outputs.index("hub_angle"), 0]
    assert -G.real * J * w**2 == pytest.approx(1.0, rel=1e-3)  # the first mode's share ~ (w / w1)^2 = 5e-6


def test_truncating_nothing_gives_the_full_response_and_keeping_more_lowers_the_error(link):
    sm, C = foam(link, 4, {"kind": "modal", "axial": 0.01, "transverse": 0.01})
    lm = voltage_model(link, sm, "FOAM", QUANSER_SRV02, 0.0, C)
    bending = voltage_model(link, sm, "SFOAM", QUANSER_SRV02, 0.0, C)  # without FOAM's stiff axial modes
    everything = modal_truncation(bending, 1e7)
    # the same model in other coordinates: rounding only. A backward error eps |A| of the Schur form
    # and the Sylvester solution moves the response by about eps |A| / (distance to the nearest
    # pole), at least the first mode's damping 0.01 w1: 100 times that bound (measured 1.8e-9)
    w1 = 2 * np.pi * 4.6
    assert response_error(bending, everything, 1000.0).value < 100 * EPS * np.abs(bending.A).max() / (0.01 * w1)
    errors = [response_error(lm, modal_truncation(lm, cut), 25.0, lowest=0.3).value for cut in (25.0, 100.0, 250.0)]
    assert errors[0] > errors[1] > errors[2]
    reduced, error = reduce_for_sampling(lm, 0.02)
    assert reduced.A.shape[0] == 6 and error.limit == 25.0 and error.lowest == pytest.approx(0.1 * 4.63, rel=1e-2)
    assert set(error.per_output) == set(lm.outputs) and error.value == max(error.per_output.values())


# --- light-hub mode names ---------------------------------------------------------------------------------


def test_every_free_hub_bending_mode_is_named_apart_on_a_light_hub(_study_config):
    """The paper's beam on a hub of 1 kg m2 (the beam's own inertia about the hub is 41 kg m2): the
    dominant coordinate of every free-hub bending mode is the first clamped-free function, so
    naming by content alone calls them all 'bending 1'; the Campbell dataset numbers them by
    frequency at every speed. With the hub held (and the paper's heavy hub) the names are those of
    the dominant coordinates."""
    beam = dataclasses.replace(BeamParameters.from_config(_study_config), Jh=1.0)
    speeds = np.linspace(0.0, 2.0, 5)
    sm = assemble(beam, None, 4)
    modes, names = datasets.tracked_modes(beam, sm, "FOAM", "free", speeds)
    content = tracking.dominant_content(modes.shape, names, modes.weights, modes.rigid)[0]
    assert list(content[0]).count("bending 1") == 4
    ds = datasets.campbell(tip_mass_axis(beam, [0.0], 4), speeds)
    free = ds.sel(hub="free", tip_mass=0.0)
    for model in ds.model.values:
        for k in range(speeds.size):
            one = free.sel(model=model).isel(speed=k)
            bending = one.label.values[[str(v).startswith("bending") for v in one.label.values]]
            frequency = one.frequency.values[[str(v).startswith("bending") for v in one.label.values]]
            assert sorted(bending) == [f"bending {i}" for i in range(1, 5)]
            assert list(bending[np.argsort(frequency)]) == [f"bending {i}" for i in range(1, 5)]
    held = ds.sel(hub="held", tip_mass=0.0, model="FOAM")
    modes, names = datasets.tracked_modes(beam, sm, "FOAM", "prescribed", speeds)
    np.testing.assert_array_equal(held.label.values[:, :modes.shape.shape[1]],
                                  tracking.dominant_content(modes.shape, names, modes.weights, modes.rigid)[0])
