"""Sampled controllers in the convention of the compiled loop: the matrices the kernel runs.

The loop (``docs/rig-design.md``, section "The sampled loop"), at each sample ``t_k = k Ts``: the
sensors give ``m_k`` (``s_j = gain_j c_j . x``, ``c_j`` a row on the simulated model's state
``x = (y, v)``, ``y = (theta, q1, q2)``), the reference ``rho_k = (theta_r, theta_r', theta_r'')``,

    e_k     = m_k - R_m rho_k
    xhat_k  = E xc_k + F e_k
    u_cmd_k = U_r . rho_k - K . xhat_k,     u_k = clip(u_cmd_k, -u_max, u_max)
    xc_{k+1} = Ac xc_k + Bc e_k + Bu (u_k - U_r . rho_k)

and ``u_k`` reaches the plant at ``t_k + D Ts`` through a zero-order hold (``u_init`` before). The
design model's state ``xhat`` is the deviation from the reference state (the rigid motion: the hub
angle ``theta_r`` and speed ``theta_r'``, every elastic coordinate and rate zero), so ``R_m``'s row
of a sensor is its reading of that motion: ``gain_j (c_j[theta], c_j[theta'], 0)``. ``U_r`` is a
feedforward on the reference (zero by default; :func:`rigid_feedforward` gives the rigid body's
``(0, c / kV, J / kV)``).

:class:`SampledController` holds ``Ac, Bc, Bu, E, F, K, R_m, U_r, xc0`` with ``Ts, D, u_max,
u_init``, the sensors and their rows ``c_j`` on the simulated model's state, built from

* :func:`state_controller`: LQR on the true state of the design (a bound): exact sensors that read
  the design's plant states (rows of the simulated model: its own state, or the output whose row
  is that state in the design model, the deflection angle for the lumped model's ``alpha``);
  ``F = I`` on them; the delayed commands of a delayed design are the controller's states
  (``Ac`` the shift, ``Bu`` feeds the newest), ``E`` puts them into ``xhat``;
* :func:`kalman_controller`: LQR and a Kalman filter (``hubbeam.control.kalman``): predictor
  ``E = I, F = 0, Ac = Ad - L Cm, Bc = L, Bu = Bd``; current estimate ``E = I - M Cm, F = M,
  Ac = Ad (I - M Cm), Bc = Ad M, Bu = Bd``;
* :func:`filtered_difference_controller`: the Quanser courseware's loop: gains on two measured
  angles (hub, deflection) and their rates, each rate a first-order low-pass (cut-off ``w_c``) of
  the backward difference, ``r_k = a r_{k-1} + (1 - a) (e_k - e_{k-1}) / (gain Ts)``,
  ``a = exp(-w_c Ts)``: exact for a ramp once settled; ``xc = (e_{k-1}, r_{k-1})``, ``Bu = 0``.

The sensor rows come from the simulated model's linear output rows (another model than the
design's, with more modes, may be simulated); the design from the design model.
:func:`closed_loop_matrix` is the sampled loop of the design model with a controller (saturation
ignored), for its poles.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from hubbeam.control.sampling import measurement_rows
from hubbeam.linear.statespace import model_states
from hubbeam.model.maneuvers import SensorSpec
from hubbeam.model.models import model as model_traits
from hubbeam.model.root import HUB_COORDINATE

#: the rate of each measured angle, for the filtered differences
RATE_OF = {"hub_angle": "hub_speed", "deflection_angle": "deflection_rate"}
#: the names of the reference's three components (the inputs of the exported controller)
REFERENCE = ("reference_angle", "reference_speed", "reference_acceleration")


@dataclass(frozen=True, eq=False)
class SampledController:
    """The matrices of the sampled loop (module docstring), in its order and under its names, with
    ``sensors``, their ``sensor_rows`` (p, 2N) on the simulated model's state, the names of the
    controller's states ``controller_states`` and of ``xhat`` (``estimate_states``), the design
    model ``design`` (a ``DiscreteModel``), the predicted ``poles`` of the design's sampled loop and
    the ``kind`` of controller."""

    Ac: np.ndarray
    Bc: np.ndarray
    Bu: np.ndarray
    E: np.ndarray
    F: np.ndarray
    K: np.ndarray
    R_m: np.ndarray
    U_r: np.ndarray
    xc0: np.ndarray
    Ts: float
    D: float
    u_max: float
    u_init: float
    sensors: tuple
    sensor_rows: np.ndarray
    controller_states: tuple[str, ...]
    estimate_states: tuple[str, ...]
    design: object
    poles: np.ndarray
    kind: str

    @property
    def matrices(self) -> dict:
        """The kernel's matrices by name, in the convention's order."""
        return {name: getattr(self, name) for name in ("Ac", "Bc", "Bu", "E", "F", "K", "R_m", "U_r", "xc0")}


def kernel_layout(simulated) -> tuple[str, ...]:
    """The names of the kernel's state ``x = (y, v)``, ``y = (theta, q1_1..n, q2_1..n)`` and the hub
    angle ``phi`` last with a root spring, for the simulated linear model (``n`` its number of
    modes; SFOAM's ``q1`` slots included)."""
    n = sum(1 for name in simulated.states if name.startswith("q2_") and not name.endswith("_dot"))
    return model_states(model_traits("FOAM"), n, simulated.root_spring)


def _on_layout(simulated, row: np.ndarray) -> np.ndarray:
    layout = kernel_layout(simulated)
    unknown = [name for name in simulated.states if name not in layout]
    if unknown:
        raise ValueError(f"simulated = {simulated.name}: state {unknown[0]!r} is not one of the assumed-modes "
                         "models' (theta, q1_k, q2_k and their rates); allowed: a linear model of TLAM, FOAM, SFOAM "
                         "or CFOAM")
    out = np.zeros(len(layout))
    for name, value in zip(simulated.states, row):
        out[layout.index(name)] = value
    return out


def sensor_rows(simulated, sensors) -> np.ndarray:
    """``c_j`` (p, 2N): the sensors' signals as rows on the kernel's state of the simulated model:
    the unit row of a state the sensor reads exactly (its signal a state of ``simulated``), else its
    linear output row; without the sensor gains, which the kernel applies."""
    layout = kernel_layout(simulated)
    return np.array([np.eye(len(layout))[layout.index(sensor.signal)] if sensor.signal in simulated.states
                     else _on_layout(simulated, measurement_rows(simulated, [SensorSpec(sensor.signal)])[0])
                     for sensor in sensors])


def reference_rows(rows: np.ndarray, sensors, layout) -> np.ndarray:
    """``R_m`` (p, 3): each sensor's reading of the rigid reference motion, ``gain (c[theta],
    c[theta'], 0)`` with ``c`` its row on the kernel's state ``layout`` (``theta`` first, ``theta'``
    at ``N``); with a root spring the hub angle ``phi`` follows the reference like ``theta``:
    ``gain (c[theta] + c[phi], c[theta'] + c[phi'], 0)``."""
    N = rows.shape[1] // 2
    hub = layout.index(HUB_COORDINATE) if HUB_COORDINATE in layout else 0

    def reading(row, i):
        return row[i] + row[i + hub] if hub else row[i]

    return np.array([[sensor.gain * reading(row, 0), sensor.gain * reading(row, N), 0.0]
                     for sensor, row in zip(sensors, rows)])


def rigid_feedforward(inertia: float, motor=None) -> np.ndarray:
    """``U_r`` that drives the rigid body along the reference: ``(0, c / kV, J / kV)`` for a drive
    (``c`` its hub damping, ``kV`` its torque gain), ``(0, 0, J)`` for a torque input; ``inertia``
    ``J`` the whole body's about the hub axis (kg m2)."""
    if not (math.isfinite(inertia) and inertia > 0.0):
        raise ValueError(f"inertia = {inertia!r}; allowed: a finite inertia > 0 kg m2")
    if motor is None:
        return np.array([0.0, 0.0, float(inertia)])
    return np.array([0.0, motor.hub_damping, float(inertia)]) / motor.torque_gain


def _loop_settings(u_max, u_init, feedforward) -> tuple[float, float, np.ndarray]:
    if not (isinstance(u_max, numbers.Real) and u_max > 0.0 and not math.isnan(u_max)):
        raise ValueError(f"u_max = {u_max!r}; allowed: a command limit > 0 (inf: none)")
    if not (isinstance(u_init, numbers.Real) and math.isfinite(u_init)):
        raise ValueError(f"u_init = {u_init!r}; allowed: a finite command")
    U_r = np.zeros(3) if feedforward is None else np.asarray(feedforward, dtype=float)
    if U_r.shape != (3,) or not np.all(np.isfinite(U_r)):
        raise ValueError(f"feedforward = {feedforward!r}; allowed: three finite coefficients on (theta_r, "
                         "theta_r', theta_r'')")
    return float(u_max), float(u_init), U_r


def closed_loop_matrix(dm, Cm: np.ndarray, Ac, Bc, Bu, E, F, K) -> np.ndarray:
    """The sampled loop of the design model ``dm`` measured by the rows ``Cm`` with a controller,
    saturation ignored: the state ``(x, xc)`` advances by ``[[Ad - Bd K F Cm, -Bd K E], [Bc Cm -
    Bu K F Cm, Ac - Bu K E]]``."""
    b, Bu = dm.B[:, :1], np.asarray(Bu).reshape(-1, 1)
    KF, KE = (K @ F)[None, :], (K @ E)[None, :]
    top = np.hstack([dm.A - b @ KF @ Cm, -b @ KE])
    bottom = np.hstack([Bc @ Cm - Bu @ KF @ Cm, Ac - Bu @ KE])
    return np.vstack([top, bottom])


def _controller(design, simulated, sensors, matrices, xc0, settings, names, estimate_states, poles, kind):
    Ac, Bc, Bu, E, F, K = matrices
    u_max, u_init, U_r = settings
    rows = sensor_rows(simulated, sensors)
    R_m = reference_rows(rows, sensors, kernel_layout(simulated))
    return SampledController(Ac=Ac, Bc=Bc, Bu=Bu, E=E, F=F, K=K, R_m=R_m, U_r=U_r,
                             xc0=xc0, Ts=design.Ts, D=design.delay, u_max=u_max, u_init=u_init, sensors=tuple(sensors),
                             sensor_rows=rows, controller_states=tuple(names), estimate_states=tuple(estimate_states),
                             design=design, poles=poles, kind=kind)


def _exact_sensor(design, simulated, name: str) -> SensorSpec:
    """The exact sensor of the design's plant state ``name``: the output whose row in the design
    model is that state (the lumped model's ``alpha`` is the deflection angle), also an output of
    the simulated model."""
    lm = design.continuous
    column = lm.states.index(name)
    for k, output in enumerate(lm.outputs):
        row = np.asarray(lm.C)[k]
        unit = np.zeros_like(row)
        unit[column] = 1.0
        if np.array_equal(row, unit) and np.all(np.asarray(lm.D)[k] == 0.0) and output in simulated.outputs:
            return SensorSpec(output)
    raise ValueError(f"the design's state {name!r} is neither a state nor a signal of the simulated model "
                     f"{simulated.name}; allowed: a design whose states are the simulated model's states or "
                     "outputs of both models (hub_angle, hub_speed, deflection_angle, deflection_rate, ...)")


def state_controller(lqr, simulated, u_max: float = math.inf, u_init: float = 0.0,
                     feedforward=None) -> SampledController:
    """LQR ``lqr`` (``hubbeam.control.dlqr.LqrDesign``) on the true state of its design model, read
    by exact sensors from the simulated model (module docstring). ``simulated`` is the simulated
    model's free-hub linear model with the outputs the sensors need (all by default)."""
    settings = _loop_settings(u_max, u_init, feedforward)
    dm = lqr.model
    n, size = dm.plant_states, dm.A.shape[0]
    readings = [SensorSpec(name) if name in simulated.states else _exact_sensor(dm, simulated, name)
                for name in dm.states[:n]]
    lags = size - n
    matrices = (dm.A[n:, n:], np.zeros((lags, n)), dm.B[n:, 0].copy(),
                np.vstack([np.zeros((n, lags)), np.eye(lags)]), np.vstack([np.eye(n), np.zeros((lags, n))]), lqr.K)
    # the design's loop and, at 0, the difference between the plant's delayed commands and the
    # controller's copy of them (neither seen nor moved)
    poles = np.concatenate([np.linalg.eigvals(dm.A - np.outer(dm.B[:, 0], lqr.K)), np.zeros(lags)])
    return _controller(dm, simulated, readings, matrices, np.full(lags, settings[1]), settings, dm.states[n:],
                       dm.states, poles, "LQR on the true state")


def kalman_controller(lqr, kf, simulated, u_max: float = math.inf, u_init: float = 0.0,
                      feedforward=None) -> SampledController:
    """LQR ``lqr`` with the Kalman filter ``kf`` (``hubbeam.control.kalman.KalmanFilter``) of the same
    discrete model, in the filter's form (module docstring)."""
    settings = _loop_settings(u_max, u_init, feedforward)
    dm = kf.model
    if lqr.model is not dm:
        raise ValueError("lqr and kf: designed on different discrete models; allowed: both on the same one")
    size, n = dm.A.shape[0], dm.plant_states
    Bd = dm.B[:, 0]
    if kf.form == "predictor":
        E, F = np.eye(size), np.zeros((size, len(kf.sensors)))
        Ac, Bc = dm.A - kf.L @ kf.Cm, kf.L
    else:
        E, F = np.eye(size) - kf.M @ kf.Cm, kf.M
        Ac, Bc = dm.A @ E, dm.A @ kf.M
    xc0 = np.concatenate([np.zeros(n), np.full(size - n, settings[1])])
    poles = np.concatenate([np.linalg.eigvals(dm.A - np.outer(Bd, lqr.K)), np.linalg.eigvals(dm.A - kf.L @ kf.Cm)])
    return _controller(dm, simulated, kf.sensors, (Ac, Bc, Bd.copy(), E, F, lqr.K), xc0, settings, dm.states,
                       dm.states, poles, f"LQR with the {kf.form}-estimate Kalman filter")


def filtered_difference_controller(lqr, sensors, cutoff: float, simulated, u_max: float = math.inf,
                                   u_init: float = 0.0, feedforward=None) -> SampledController:
    """The courseware's loop (module docstring): the gains of ``lqr`` on a design whose plant states are
    the ``sensors``' angles (``hub_angle``, ``deflection_angle``) and their rates, the rates from
    first-order filtered differences with the cut-off ``cutoff`` (rad s-1). The gains on a delayed
    design's past commands are not used (the courseware's loop has none)."""
    settings = _loop_settings(u_max, u_init, feedforward)
    if not (isinstance(cutoff, (int, float)) and math.isfinite(cutoff) and cutoff > 0.0):
        raise ValueError(f"cutoff = {cutoff!r}; allowed: a finite cut-off frequency > 0 rad s-1")
    sensors = tuple(sensors)
    unknown = [sensor.signal for sensor in sensors if sensor.signal not in RATE_OF]
    if unknown or not sensors:
        raise ValueError(f"sensors measure {[s.signal for s in sensors]}; allowed: angles among {', '.join(RATE_OF)}")
    dm = lqr.model
    lm = dm.continuous
    names = [sensor.signal for sensor in sensors] + [RATE_OF[sensor.signal] for sensor in sensors]
    gains = []
    for name in names:
        k = lm.outputs.index(name) if name in lm.outputs else -1
        row = np.asarray(lm.C)[k] if k >= 0 else np.zeros(len(lm.states))
        if k < 0 or np.count_nonzero(row) != 1 or row.max() != 1.0:
            raise ValueError(f"the design model {lm.name} has no state that is the signal {name!r}; allowed: a "
                             "design whose states are the measured angles and their rates (the lumped model)")
        gains.append(lqr.K[int(np.argmax(row))])
    if len(lm.states) != len(names):
        raise ValueError(f"the design model {lm.name} has the states {list(lm.states)}; allowed: exactly the "
                         f"measured angles and their rates ({', '.join(names)})")
    p = len(sensors)
    a = math.exp(-cutoff * dm.Ts)
    b = (1.0 - a) / dm.Ts
    inverse = np.diag([1.0 / sensor.gain for sensor in sensors])
    Ac = np.block([[np.zeros((p, p)), np.zeros((p, p))], [-b * inverse, a * np.eye(p)]])
    Bc = np.vstack([np.eye(p), b * inverse])
    E = Ac.copy()
    F = np.vstack([inverse, b * inverse])
    K = np.array(gains)
    xc0 = np.zeros(2 * p)
    Cm = measurement_rows(dm, sensors)
    poles = np.linalg.eigvals(closed_loop_matrix(dm, Cm, Ac, Bc, np.zeros(2 * p), E, F, K))
    states = [f"{name}_previous" for name in names[:p]] + [f"{name}_filtered" for name in names[p:]]
    return _controller(dm, simulated, sensors, (Ac, Bc, np.zeros(2 * p), E, F, K), xc0, settings, states, names,
                       poles, f"LQR on filtered differences (cut-off {cutoff:g} rad/s)")


__all__ = ["REFERENCE", "SampledController", "closed_loop_matrix", "filtered_difference_controller",
           "kalman_controller", "kernel_layout", "reference_rows", "rigid_feedforward", "sensor_rows",
           "state_controller"]
