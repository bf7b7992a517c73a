"""The sampled digital controller in the kernel (``hubbeam.core.sampled``, ``hubbeam.simulation.simulate.run`` with a
``SampledLoop``), on the flexible link of ``conftest.flexible_link``.

* the analog low-pass, discretised exactly on the dense output, is the closed-form response of a
  first-order filter to a steadily spinning hub's angle; its two parts (the signal polynomial of
  a step, the weights ``J_k``) against the dense output and against quadrature;
* about a steady spin (ideal torque actuator, fractional delay) and at rest (the SRV02 drive,
  one sample of delay), the nonlinear run under an LQG controller follows the discrete linear
  loop (the linear model, ``control.sample_system`` with the delay, the same controller in
  numpy): the gap falls with the square of the amplitude;
* as the sample time goes to zero, sampled state feedback on the true state recovers the
  continuous ``state_feedback`` run with the same gains, the error of first order in ``Ts``;
* an encoder's error stays within its model's bound, and fills it;
* the records obey the convention sample by sample (the applied input is the law on the
  estimate, the estimate the controller's recursion on the measurements); the noise is the
  seed's, and the estimate departs from the true state with it;
* a delay of ``D`` samples (whole or fractional) shifts the applied input, and the motion it
  causes, by ``D Ts``;
* bad loops and sensors are refused naming the argument.
"""

import functools

import control as ct
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.interpolate import CubicSpline
from synthetic_results import rig_run

from hubbeam.configuration.settings import simulation_settings
from hubbeam.control.feedback import feedback_law
from hubbeam.core.inputs import LoopSensors
from hubbeam.core.integrate import output_columns
from hubbeam.core.maneuver import held_input, reference_motion
from hubbeam.core.radau import hermite_interpolate
from hubbeam.core.sampled import hold, lowpass_weights, signal_polynomial
from hubbeam.linear.statespace import linear_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.drive import QUANSER_SRV02
from hubbeam.model.maneuvers import SensorSpec, maneuver_from_dict
from hubbeam.model.plant import with_drive
from hubbeam.simulation.errors import SimulationError
from hubbeam.simulation.sampled import SampledLoop, reference_array
from hubbeam.simulation.simulate import case_matrices

NUMERICS = {"rtol": 1e-10, "atol": 1e-12, "output_step": 0.01, "max_steps": 10**7, "step_warning": 10**7,
            "divergence_limit": 0.5, "quadrature_points": 40}
DAMPED = {"kind": "modal", "axial": 0.02, "transverse": 0.02}
MODES = 2
N = 1 + 2 * MODES
#: a reference at steady spin from t = 0: Eq. 43 over a vanishing tf (its angle lags by wf tf / 2)
SPEED = 2.0
STEADY = {"kind": "prescribed", "wf": SPEED, "tf": 1e-9}
#: a reference at rest
REST = {"kind": "angle_table", "time": [0.0, 1.0], "angle": [0.0, 0.0]}


def _case(reference, model="FOAM", t_end=1.0, **extra):
    """A case whose tracking maneuver gives the loop its reference (its own gains unused)."""
    return {"name": "sampled", "model": model, "modes": MODES, "t_end": t_end, "damping": DAMPED,
            "maneuver": {"kind": "pd", "kp": 0.0, "kd": 0.0, "reference": reference}, **extra}


def _matrices(case, beam):
    """The system matrices of the case mapping ``case`` (checked, as ``simulate`` would)."""
    checked, numerics = simulation_settings(case, NUMERICS, beam.L)
    return case_matrices(checked, beam, numerics)


def _unit(index):
    row = np.zeros(2 * N)
    row[index] = 1.0
    return row


def _sensors(*pairs):
    """The sensors and their rows, as a loop takes them, of ``(SensorSpec, row)`` pairs."""
    return [sensor for sensor, _ in pairs], np.array([row for _, row in pairs])


def _feedback(sensors, K, R_m, Ts, **settings):
    """Static feedback ``u = U_r . rho - K (m - R_m rho)`` on the sensors (no controller state)."""
    p = len(sensors[0])
    return SampledLoop(*sensors, np.zeros((0, 0)), np.zeros((0, p)), np.zeros(0), np.zeros((p, 0)), np.eye(p),
                       np.asarray(K, float), np.asarray(R_m, float), settings.pop("U_r", np.zeros(3)),
                       np.zeros(0), Ts=Ts, **settings)


# --------------------------------------------------------------------------- the analog low-pass
@pytest.mark.parametrize("r", [1e-7, 0.3, 1.99, 2.01, 7.0, 300.0])
def test_the_lowpass_weights_are_their_integrals(r):
    weights = np.empty(6)
    lowpass_weights(r, weights)
    # quadrature to 1e-13 relative (beyond it scipy refuses); its nodes gathered near s = 1, where
    # exp(-r (1 - s)) lives for large r
    crowded = {"points": [1.0 - 10.0 / r]} if r > 10.0 else {}
    for k in range(6):
        exact, _ = quad(lambda s, k=k: r * np.exp(-r * (1.0 - s)) * s**k, 0.0, 1.0, epsabs=0.0, epsrel=1e-13,
                        limit=200, **crowded)
        assert weights[k] == pytest.approx(exact, rel=1e-12)


def test_the_signal_polynomial_is_the_dense_output():
    rng = np.random.default_rng(5)
    nf, h = 4, 0.37
    start, end = tuple(rng.normal(size=nf) for _ in range(3)), tuple(rng.normal(size=nf) for _ in range(3))
    sensors = LoopSensors(rng.normal(size=(1, 2 * nf)), np.array([1.7]), np.array([-0.4]), np.zeros(1),
                          np.ones(1), np.zeros(1), np.zeros(1, np.int64), np.zeros((1, 1)))
    poly = np.empty(6)
    signal_polynomial(sensors, 0, h, start, end, poly)
    y, v = np.empty(nf), np.empty(nf)
    for s in np.linspace(0.0, 1.0, 9):
        hermite_interpolate(s, h, start, end, y, v)
        expected = 1.7 * (sensors.rows[0, :nf] @ y + sensors.rows[0, nf:] @ v) - 0.4
        assert np.polynomial.polynomial.polyval(s, poly) == pytest.approx(expected, rel=1e-13, abs=1e-13)


def test_the_lowpass_is_exact_on_a_steadily_spinning_hub(flexible_link):
    """Without input the hub spins on at ``theta = W t``; a first-order low-pass of time constant
    tau starting in equilibrium gives ``W (t - tau (1 - exp(-t / tau)))``. The steps of h = Ts =
    0.01 s make ``h / tau`` 5 for the fast filter (the weights' recurrence) and 0.2 for the slow
    one (their series); the first steps, growing from 1e-6 s, take the series for both."""
    sensors = _sensors((SensorSpec("fast", lowpass=0.002), _unit(0)), (SensorSpec("slow", lowpass=0.05), _unit(0)),
                       (SensorSpec("raw"), _unit(0)))
    loop = SampledLoop(*sensors, *(np.zeros(shape) for shape in ((0, 0), (0, 3), 0, (0, 0), (0, 3), 0)),
                       np.zeros((3, 3)), np.zeros(3), np.zeros(0), Ts=0.01)
    run = rig_run(_case(STEADY, t_end=1.0, initial={"hub_speed": SPEED}), flexible_link, NUMERICS,
                       loop=loop)
    t = run.records.t
    sensed = run.records.sensed
    # theta'' = 0 holds to rounding at the steady spin, the angle grows to 2 rad
    np.testing.assert_allclose(sensed[:, 2], SPEED * t, rtol=0, atol=1e-13)
    for j, tau in enumerate((0.002, 0.05)):
        np.testing.assert_allclose(sensed[:, j], SPEED * (t - tau * -np.expm1(-t / tau)), rtol=0, atol=1e-13)


# --------------------------------------------------------------------------- the discrete linear loop
def _linear_plant(flexible_link, case, motor):
    """The simulated model's linear model about its steady spin (``linear_model``, free hub) with
    the hub angle and the root moment as outputs; with a drive, its input is the voltage: the
    torque ``torque_gain V - hub_damping theta'`` (no Coulomb friction) about the spin's voltage."""
    sm = with_drive(_matrices(case, flexible_link), motor)
    lin = linear_model(flexible_link, sm, case["model"], SPEED, "free", damping_matrices(DAMPED, sm),
                       outputs=["hub_angle", "root_moment"])
    A, B = lin.A, lin.B
    if motor is not None:
        A = A - motor.hub_damping * B @ _unit(N)[None, :]
        B = motor.torque_gain * B
    return lin, ct.ss(A, B, lin.C, 0)


def _lqg(plant, Ts, input_weight, bias):
    """A predictor LQG on the ZOH model (``ct.dlqr``, ``ct.dlqe``) in the convention's form ``E = I,
    F = 0, Ac = Ad - L Cd, Bc = L, Bu = Bd``, with one more controller state held at 1 that adds
    ``bias`` to the command (the voltage of the steady spin) and keeps it out of the observer."""
    sysd = ct.sample_system(plant, Ts)
    Ad, Bd, Cd = sysd.A, sysd.B[:, 0], sysd.C
    ns = Ad.shape[0]
    K, _, _ = ct.dlqr(Ad, sysd.B, Cd.T @ np.diag([100.0, 1e4]) @ Cd + 1e-3 * np.eye(ns), input_weight)
    L, _, _ = ct.dlqe(Ad, np.eye(ns), Cd, 1e-6 * np.eye(ns), np.diag([1e-6, 1e-8]))
    Ac = np.zeros((ns + 1, ns + 1))
    Ac[:ns, :ns] = Ad - L @ Cd
    Ac[:ns, ns] = -Bd * bias
    Ac[ns, ns] = 1.0
    controller = {"Ac": Ac, "Bc": np.vstack([L, np.zeros((1, 2))]), "Bu": np.append(Bd, 0.0),
                  "E": np.eye(ns + 1), "F": np.zeros((ns + 1, 2)), "K": np.append(K[0], -bias),
                  "R_m": np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]), "U_r": np.zeros(3),
                  "xc0": np.append(np.zeros(ns), 1.0)}
    assert np.abs(np.linalg.eigvals(Ad - sysd.B @ K)).max() < 1.0  # the design is stable
    assert np.abs(np.linalg.eigvals(Ad - L @ Cd)).max() < 1.0
    return controller


def _discrete_loop(plant, controller, loop, x0, reference, samples):
    """The loop of the convention on the linear plant, in numpy: the plant sampled with a ZOH
    delayed by ``D = d + f`` samples (``ct.sample_system`` over ``(1 - f) Ts`` and ``f Ts``: over
    ``[t_k, t_(k+1))`` the command of sample ``k - d - 1`` acts until ``t_k + f Ts``, that of ``k -
    d`` after). Returns the applied inputs ``u_k``, as deviations from the steady input."""
    Ts, D, bias = loop.Ts, loop.D, loop.u_init
    d, f = int(np.floor(D)), D - np.floor(D)
    whole = ct.sample_system(plant, Ts)
    if f > 0.0:
        late, early = ct.sample_system(plant, (1.0 - f) * Ts), ct.sample_system(plant, f * Ts)
        new, old = late.B[:, 0], late.A @ early.B[:, 0]
    else:
        new, old = whole.B[:, 0], np.zeros(whole.A.shape[0])
    x, xc = x0.copy(), controller["xc0"].copy()
    u = np.zeros(samples)
    for k in range(samples):
        t = k * Ts
        theta_r = reference_motion(t, reference, 1)[0]
        e = plant.C @ x + np.array([SPEED * t - theta_r, 0.0])  # the angle from its reference
        xhat = controller["E"] @ xc + controller["F"] @ e
        u[k] = -controller["K"] @ xhat  # U_r = 0, no saturation
        xc = controller["Ac"] @ xc + controller["Bc"] @ e + controller["Bu"] * u[k]
        u[k] -= bias
        x = whole.A @ x + new * (u[k - d] if k >= d else 0.0) + old * (u[k - d - 1] if k > d else 0.0)
    return u


@pytest.mark.parametrize("model, motor, delay", [("FOAM", None, 0.5), ("CFOAM", QUANSER_SRV02, 1.0)],
                         ids=["FOAM-torque-half-sample", "CFOAM-SRV02-one-sample"])
def test_about_a_steady_spin_the_sampled_run_follows_the_discrete_linear_loop(flexible_link, model, motor,
                                                                             delay):
    """From the steady spin at 2 rad/s plus ``q2_1 = a`` the nonlinear run and the discrete linear
    loop (same controller, same delay) differ by the equations' nonlinear terms, quadratic in the
    deviation: the gap in the applied input falls to a quarter (within 10 %, the cubic terms'
    share at these amplitudes; measured 3.95 and 4.08) when ``a`` halves, and is below 1e-3 of the
    input (measured 2.9e-4 and 5.0e-5 at a = 2e-4, FOAM and CFOAM; the integrator's share, at
    rtol 1e-10, is far below, and the same quarter holds down to a = 5e-5)."""
    Ts = 0.002
    case = _case(STEADY, model, t_end=1.5)
    lin, plant = _linear_plant(flexible_link, case, motor)
    bias = 0.0 if motor is None else motor.hub_damping * SPEED / motor.torque_gain
    controller = _lqg(plant, Ts, 100.0 if motor is None else 1.0, bias)
    loop = SampledLoop([SensorSpec("hub_angle"), SensorSpec("root_moment")], lin.C[:2], **controller, Ts=Ts,
                       D=delay, u_init=bias)
    gaps = []
    for amplitude in (2e-4, 1e-4):
        run = rig_run(dict(case, initial={"hub_speed": SPEED, "q2": [amplitude, 0.0]}), flexible_link,
                           NUMERICS, motor=motor, loop=loop)
        x0 = np.zeros(2 * N)
        x0[lin.states.index("q2_1")] = amplitude
        reference = reference_array(maneuver_from_dict(case["maneuver"]))
        u = _discrete_loop(plant, controller, loop, x0, reference, run.records.t.size)
        gap = np.abs(run.records.applied - bias - u).max()
        assert gap < 1e-3 * np.abs(u).max()
        gaps.append(gap)
    assert 3.6 < gaps[0] / gaps[1] < 4.4


# --------------------------------------------------------------------------- the continuous limit
def test_a_vanishing_sample_time_recovers_the_continuous_state_feedback(flexible_link):
    """LQR gains (designed on SFOAM: none on q1) applied continuously by the ``state_feedback``
    maneuver, and sampled at Ts with exact sensors on the states they weigh (``F = I``): the zero-
    order hold lags the continuous law by Ts / 2 on average, so the tip deflection's error is of
    first order in Ts: measured orders 0.963 and 0.982, the next term (of second order) halving
    their departure from 1 as Ts halves. The fastest closed-loop pole, 149 rad/s, is well inside
    the sampling (Ts |p| <= 0.6)."""
    maneuver = {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.5, "tf": 1.0},
                "design": {"model": "SFOAM", "speed": 1.5, "torque_weight": 10.0,
                           "weights": {"hub_angle": 10.0, "hub_speed": 0.1, "tip_deflection": 1e3}}}
    case = {"name": "limit", "model": "FOAM", "modes": MODES, "t_end": 2.0, "damping": DAMPED,
            "maneuver": maneuver}
    feedback = functools.partial(feedback_law, beam=flexible_link)
    continuous = rig_run(case, flexible_link, NUMERICS, feedback=feedback)
    tip = output_columns(MODES)["tip_transverse"]
    gains = feedback(simulation_settings(case, NUMERICS, flexible_link.L)[0], _matrices(case, flexible_link))[0].gains
    weighed = np.flatnonzero(gains)
    assert not set(weighed) & {1, 2, N + 1, N + 2}  # no q1 gains: their reference is not sampled
    R_m = np.zeros((weighed.size, 3))
    R_m[weighed == 0, 0] = 1.0  # theta against theta_r
    R_m[weighed == N, 1] = 1.0  # theta' against theta_r'
    errors = []
    for Ts in (0.004, 0.002, 0.001):
        loop = _feedback(_sensors(*((SensorSpec(f"x{i}"), _unit(i)) for i in weighed)), gains[weighed], R_m, Ts)
        sampled = rig_run(case, flexible_link, NUMERICS, loop=loop)
        errors.append(np.abs(sampled.out[:, tip] - continuous.out[:, tip]).max())
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    np.testing.assert_allclose(orders, 1.0, atol=0.05)
    assert abs(orders[1] - 1.0) < abs(orders[0] - 1.0)
    assert errors[-1] < 0.01 * np.abs(continuous.out[:, tip]).max()


# --------------------------------------------------------------------------- sensors and records
def _spin_up(Ts=0.002, t_end=2.0):
    """A case spinning the hub up to 1.5 rad/s in 1 s (the reference of the loops below)."""
    return _case({"kind": "prescribed", "wf": 1.5, "tf": 1.0}, t_end=t_end)


def test_an_encoder_stays_within_its_model_s_bound(flexible_link):
    """A 4096-count encoder on the hub angle, read rounding and counting edges, on a PD loop on
    the rounded reading: the rounded reading is within half a count of the angle, the counted one
    below it by less than a count; over a spin-up both errors fill their intervals. The bounds
    allow the rounding of ``q * round(s / q)`` (a few ulps of the angle)."""
    quantum = 2.0 * np.pi / 4096
    sensors = _sensors((SensorSpec("rounded", quantum=quantum), _unit(0)),
                       (SensorSpec("counted", quantum=quantum, mode="edges"), _unit(0)),
                       (SensorSpec("speed"), _unit(N)))
    loop = _feedback(sensors, [2.0, 0.0, 0.3], [[1.0, 0, 0], [1.0, 0, 0], [0, 1.0, 0]], 0.002)
    records = rig_run(_spin_up(), flexible_link, NUMERICS, loop=loop).records
    slack = 8 * np.spacing(np.abs(records.sensed[:, :2]).max())
    rounded = records.measured[:, 0] - records.sensed[:, 0]
    counted = records.sensed[:, 1] - records.measured[:, 1]
    assert np.abs(rounded).max() <= quantum / 2 + slack
    assert np.all(counted >= -slack) and np.all(counted < quantum + slack)
    np.testing.assert_allclose(records.measured[:, :2] / quantum, np.round(records.measured[:, :2] / quantum),
                               rtol=0, atol=1e-9)
    assert np.abs(rounded).max() > 0.45 * quantum and counted.max() > 0.9 * quantum and counted.min() < 0.1 * quantum


def _current_estimator(flexible_link, case, Ts, noise, seed=0, u_max=np.inf):
    """A current-estimator LQG (``E = I - M Cd``, ``F = M``, ``Ac = Ad (I - M Cd)``, ``Bc = Ad M``,
    ``Bu = Bd``) designed on the FOAM model at rest, with the hub angle's and root moment's noise
    ``noise`` (rad, N m), and the feedforward ``J theta_r''`` on the reference of ``case``; the
    estimate starts at the case's initial bending (``xc0``)."""
    sm = _matrices(case, flexible_link)
    lin = linear_model(flexible_link, sm, "FOAM", 0.0, "free", damping_matrices(DAMPED, sm),
                       outputs=["hub_angle", "root_moment"])
    sysd = ct.sample_system(lin.to_control(), Ts)
    Ad, Bd, Cd = sysd.A, sysd.B, sysd.C
    ns = Ad.shape[0]
    K, _, _ = ct.dlqr(Ad, Bd, Cd.T @ np.diag([100.0, 1e4]) @ Cd + 1e-3 * np.eye(ns), 100.0)
    RN = np.diag([1e-6, 1e-8])
    _, P, _ = ct.dlqe(Ad, np.eye(ns), Cd, 1e-6 * np.eye(ns), RN)  # P: the predicted covariance
    M = P @ Cd.T @ np.linalg.inv(Cd @ P @ Cd.T + RN)
    sensors = [SensorSpec("hub_angle", noise=noise[0]), SensorSpec("root_moment", noise=noise[1])]
    inertia = float(sm.Jh + sm.Jb)
    start = np.zeros(ns)
    start[[lin.states.index("q2_1"), lin.states.index("q2_2")]] = case.get("initial", {}).get("q2", (0.0, 0.0))
    loop = SampledLoop(sensors, lin.C[:2], Ad @ (np.eye(ns) - M @ Cd), Ad @ M, Bd[:, 0], np.eye(ns) - M @ Cd, M, K[0],
                       [[1.0, 0, 0], [0, 0, 0]], [0.0, 0.0, inertia], start, Ts=Ts, u_max=u_max, seed=seed)
    return lin, loop


def test_the_records_obey_the_convention_sample_by_sample(flexible_link):
    """From the records alone: ``rho_k`` of the reference, ``e_k = m_k - R_m rho_k``, the
    controller's recursion gives ``xhat_k``, the law ``u_cmd_k`` and its saturation ``u_k`` (to
    the rounding of the recomputation, relative to the sizes of the terms summed); the saturation
    binds in the spin-up; the noise is the seed's ``sigma w``."""
    case = _spin_up()
    _, loop = _current_estimator(flexible_link, case, 0.002, (1e-3, 1e-4), seed=7, u_max=0.02)
    run = rig_run(case, flexible_link, NUMERICS, loop=loop)
    records = run.records
    reference = reference_array(maneuver_from_dict(case["maneuver"]))
    xc = loop.xc0.copy()
    for k, t in enumerate(records.t):
        assert t == k * loop.Ts
        rho = np.array(reference_motion(t, reference, 1))
        e = records.measured[k] - loop.R_m @ rho
        xhat = loop.E @ xc + loop.F @ e
        # the sums cancel: their rounding is relative to the sums of the terms' sizes
        size = np.abs(loop.E) @ np.abs(xc) + np.abs(loop.F) @ np.abs(e)
        assert np.all(np.abs(records.estimate[k] - xhat) <= 1e-12 * size)
        command = loop.U_r @ rho - loop.K @ xhat
        assert abs(records.command[k] - command) <= 1e-12 * (np.abs(loop.U_r) @ np.abs(rho) + np.abs(loop.K) @ size)
        assert records.applied[k] == np.clip(records.command[k], -loop.u_max, loop.u_max)
        xc = loop.Ac @ xc + loop.Bc @ e + loop.Bu * (records.applied[k] - loop.U_r @ rho)
    assert np.any(np.abs(records.command) > loop.u_max)
    sigma = np.array([sensor.noise for sensor in loop.sensors])
    np.testing.assert_array_equal(run.noise, np.random.default_rng(7).standard_normal(run.noise.shape))
    np.testing.assert_allclose(records.measured - records.sensed, sigma * run.noise, rtol=1e-9, atol=1e-17)


def test_noise_moves_the_estimate_off_the_state_and_is_the_seed_s(flexible_link):
    """At rest, from a bent link (``q2_1 = 2e-3``), the estimate ``xhat`` against the true state
    (at the output times, one per sample): with exact sensors only the nonlinear terms the design
    model lacks set them apart (measured 1e-8 to 6e-8); noisy sensors (1 mrad, 0.1 mN m) move the
    estimate a hundred times further off at least (measured 1700 to 21000 times);
    the same seed gives the same records, bit for bit, another seed others."""
    Ts = 0.002
    case = _case(REST, initial={"q2": [2e-3, 0.0]})
    runs = {}
    for label, noise, seed in (("exact", (0.0, 0.0), 0), ("noisy", (1e-3, 1e-4), 0), ("again", (1e-3, 1e-4), 0),
                               ("other", (1e-3, 1e-4), 1)):
        lin, loop = _current_estimator(flexible_link, case, Ts, noise, seed)
        runs[label] = rig_run(case, flexible_link, dict(NUMERICS, output_step=Ts), loop=loop)
    columns = output_columns(MODES)
    reference = reference_array(maneuver_from_dict(case["maneuver"]))

    def estimation_error(run):
        """RMS over the samples of the estimate's hub angle and bending coordinates less the
        state's (their deviations from the reference: the design model is linearised at rest)."""
        t, out = run.records.t, run.out
        assert np.array_equal(run.t, t)  # an output time per sample
        theta_r = np.array([reference_motion(tk, reference, 1)[0] for tk in t])
        true = np.column_stack([out[:, columns["theta"]] - theta_r, out[:, columns["q2"]]])
        estimate = run.records.estimate[:, [lin.states.index(name) for name in ("theta", "q2_1", "q2_2")]]
        return np.sqrt(np.mean((estimate - true) ** 2, axis=0))

    assert np.all(estimation_error(runs["noisy"]) > 100.0 * estimation_error(runs["exact"]))
    for field in runs["noisy"].records._fields:
        np.testing.assert_array_equal(getattr(runs["again"].records, field), getattr(runs["noisy"].records, field))
    assert not np.array_equal(runs["other"].records.measured, runs["noisy"].records.measured)


# --------------------------------------------------------------------------- the delay
def test_a_delay_of_d_samples_shifts_the_input_and_the_motion_by_d_ts(flexible_link):
    """A feedforward loop (``K = 0``, ``u_k = J theta_r''(t_k)``) gives the same commands whatever
    the delay. With ``D`` samples of delay the hub torque (an ideal actuator: the held input) is,
    at every output time, the command of the last switch ``(k + D) Ts`` before it, ``u_init = 0``
    before the first, bit for bit; and the motion from rest is the undelayed one shifted by ``D Ts``,
    to the integrator's error on different steps: measured 2.7e-10 of the hub angle (where rtol
    1e-10 rules) and 9e-9 of the tip deflection (where atol 1e-12 on q2 of 3e-4 rules)."""
    Ts, step = 0.004, 0.001
    case = _spin_up(t_end=1.5)
    sm = _matrices(case, flexible_link)
    inertia = float(sm.Jh + sm.Jb)
    columns = output_columns(MODES)
    runs = {}
    for D in (0.0, 0.25, 1.0, 2.5):
        loop = _feedback(_sensors((SensorSpec("hub_angle"), _unit(0))), [0.0], [[1.0, 0.0, 0.0]], Ts, D=D,
                         U_r=np.array([0.0, 0.0, inertia]))
        run = rig_run(case, flexible_link, dict(NUMERICS, output_step=step), loop=loop)
        switches = (np.arange(run.records.t.size) + D) * Ts
        last = np.searchsorted(switches, run.t, side="right") - 1
        held = np.where(last >= 0, run.records.applied[np.maximum(last, 0)], 0.0)
        np.testing.assert_array_equal(run.out[:, columns["hub_torque"]], held)
        # the restarts at the switches keep the Jacobian (the held input is not in it): it is
        # refreshed only where Newton converges slowly
        assert run.integrator["n_jacobian"] < 0.1 * run.records.t.size
        runs[D] = run
    reference = runs[0.0]
    np.testing.assert_array_equal(runs[2.5].records.applied, reference.records.applied)
    for D, run in runs.items():
        shift = round(D * Ts / step)
        for name, tolerance in (("theta", 1e-9), ("tip_transverse", 1e-7)):
            delayed, undelayed = run.out[shift:, columns[name]], reference.out[:run.t.size - shift, columns[name]]
            np.testing.assert_allclose(delayed, undelayed, rtol=0, atol=tolerance * np.abs(undelayed).max())
            assert np.all(run.out[:shift + 1, columns[name]] == 0.0)  # at rest until the input arrives


# --------------------------------------------------------------------------- the kernels' pieces
def test_the_reference_of_an_angle_table_has_the_spline_s_rates():
    reference = {"kind": "angle_table", "time": [0.0, 0.5, 1.5, 2.0], "angle": [0.0, 0.3, -0.2, 0.1]}
    packed = reference_array(maneuver_from_dict({"kind": "pd", "kp": 0.0, "kd": 0.0, "reference": reference}))
    spline = CubicSpline(reference["time"], reference["angle"], bc_type="clamped")
    for t in np.linspace(-0.5, 2.5, 31):
        inside = 0.0 <= t < 2.0  # from the last time on the angle is held: no rates
        expected = [spline(min(max(t, 0.0), 2.0))] + [spline(t, d) if inside else 0.0 for d in (1, 2)]
        np.testing.assert_allclose(reference_motion(t, packed, 1), expected, rtol=1e-12, atol=1e-12)


def test_the_held_input_switches_at_its_times_and_holds_between():
    mp = np.zeros(1 + 2 * 4)
    mp[0] = 1.0
    mp[1 + 4] = -1.0  # u_init from t = 0
    for t, value in ((0.0, 2.0), (0.3, 3.0), (0.7, 4.0)):
        hold(mp, t, value)
    # the last switch at or before t; the initial value only before the first switch time
    for t, value in ((-1.0, -1.0), (0.0, 2.0), (0.1, 2.0), (0.3, 3.0), (0.69, 3.0), (0.7, 4.0), (9.0, 4.0)):
        assert held_input(t, mp) == value


# --------------------------------------------------------------------------- bad input
def _good():
    return {"sensors": [SensorSpec("a"), SensorSpec("b")], "rows": np.array([_unit(0), _unit(N)]), "Ac": np.eye(1),
            "Bc": np.zeros((1, 2)), "Bu": np.zeros(1), "E": np.zeros((3, 1)), "F": np.zeros((3, 2)),
            "K": np.zeros(3), "R_m": np.zeros((2, 3)), "U_r": np.zeros(3), "xc0": np.zeros(1), "Ts": 0.002}


@pytest.mark.parametrize("key, value, message", [
    ("sensors", [], "SampledLoop.sensors = .*a non-empty list of SensorSpec"),
    ("sensors", [SensorSpec("a"), SensorSpec("a")], "distinct signals"),
    ("sensors", [SensorSpec("a"), SensorSpec("")], "sensor ''.signal = ''; allowed: a non-empty name"),
    ("sensors", [SensorSpec("a"), SensorSpec("b", noise=-1.0)], "sensor 'b'.noise = -1.0; allowed: a finite number "
                                                                ">= 0"),
    ("sensors", [SensorSpec("a", lowpass=np.nan), SensorSpec("b")], "sensor 'a'.lowpass = nan"),
    ("sensors", [SensorSpec("a", mode="floor"), SensorSpec("b")], "sensor 'a'.mode = 'floor'; allowed: one of round, "
                                                                  "edges"),
    ("sensors", [SensorSpec("a", gain="two"), SensorSpec("b")], "sensor 'a'.gain = 'two'; allowed: a finite, non-zero"),
    ("sensors", [SensorSpec("a", gain=0.0), SensorSpec("b")], "sensor 'a'.gain = 0.0; allowed: a finite, non-zero"),
    ("rows", np.ones((2, 3)), r"SampledLoop.rows: shape \(2, 3\); allowed: .*\(p, 2 N\)"),
    ("rows", np.ones((1, 4)), r"SampledLoop.rows: shape \(1, 4\); allowed: .*p = 2"),
    ("rows", [["x", "y"], ["z", "w"]], "SampledLoop.rows: .*finite values"),
    ("rows", np.ones(4), r"SampledLoop.rows: shape \(4,\)"),
    ("Bc", np.zeros((2, 2)), r"SampledLoop.Bc: shape \(2, 2\); allowed: .*\(nc, p\) = \(1, 2\)"),
    ("F", np.zeros((3, 3)), r"SampledLoop.F: shape .*\(ns, p\) = \(3, 2\)"),
    ("R_m", np.full((2, 3), np.nan), "SampledLoop.R_m: .*finite"),
    ("Ac", np.zeros((1, 2)), "SampledLoop.Ac: shape"),
    ("Ac", np.zeros(2), r"SampledLoop.Ac: shape \(2,\); allowed: a square matrix"),
    ("E", [["a"], ["b"], ["c"]], "SampledLoop.E: .*finite values"),
    ("Ts", 0.0, "SampledLoop.Ts = 0.0; allowed: a finite sample time > 0"),
    ("D", -1.0, "SampledLoop.D = -1.0; allowed: a finite delay >= 0"),
    ("D", 1.0 + 1e-9, "SampledLoop.D = .*fractional part"),
    ("u_max", 0.0, "SampledLoop.u_max = 0.0; allowed: a saturation > 0"),
    ("u_init", np.inf, "SampledLoop.u_init = inf; allowed: a finite input"),
    ("seed", -3, "SampledLoop.seed = -3; allowed: an integer >= 0"),
])
def test_a_bad_loop_is_refused_naming_the_argument(key, value, message):
    with pytest.raises(SimulationError, match=message):
        SampledLoop(**dict(_good(), **{key: value}))


def test_a_loop_needs_a_tracking_case_and_rows_of_its_model(flexible_link):
    loop = SampledLoop(**_good())
    torque = dict(_case(REST), maneuver={"kind": "torque", "tau_max": 1.0, "tf": 1.0})
    with pytest.raises(SimulationError, match="'torque' with a sampled loop; allowed: a maneuver that tracks"):
        rig_run(torque, flexible_link, NUMERICS, loop=loop)
    with pytest.raises(SimulationError, match=r"SampledLoop.rows: rows of length 10; allowed: 2 N = 14"):
        rig_run(dict(_case(REST), modes=3), flexible_link, NUMERICS, loop=loop)
