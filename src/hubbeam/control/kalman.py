"""The steady-state Kalman filter of a sampled plant, from named measured signals.

The plant is a :class:`hubbeam.linear.discrete.DiscreteModel` (zero-order hold, delayed inputs
among the states) driven by process noise and measured with noise,

    x_{k+1} = Ad x_k + Bd u_k + G w_k,     m_k = Cm x_k + v_k,     w ~ N(0, Qw),  v ~ N(0, Rv),

``Cm`` the sensors' rows ``gain c`` (:func:`hubbeam.control.sampling.measurement_rows`), ``Rv``
their variances (``noise^2 + quantum^2 / 12``; or a given matrix). The process noise acts

* on the input: a random input (torque or volts) held over each sample ``[t_k, t_{k+1})``, of
  variance ``input_noise`` (the input's unit squared): ``G = Gamma(Ts) = int_0^Ts exp(A s) ds B``
  on the plant's states (it does not pass the controller's delay);
* on named states of the plant: ``state_noise = {name: variance}``, a unit column each.

``control.dlqe`` solves the filter's discrete Riccati equation for the a-priori covariance
``P = cov(x_k - xhat_{k|k-1})`` and returns the predictor gain ``L = Ad P Cm^T (Cm P Cm^T +
Rv)^-1``. The current-estimate gain is ``M = P Cm^T (Cm P Cm^T + Rv)^-1`` (so ``L = Ad M``) and the
a-posteriori covariance ``cov(x_k - xhat_{k|k}) = (I - M Cm) P`` (Franklin, Powell and Workman,
*Digital Control of Dynamic Systems*, 1998, Sec. 8.3; Anderson and Moore, *Optimal Filtering*,
1979, Ch. 3):

* current estimate (no delay): ``xhat_{k|k} = xbar_k + M (m_k - Cm xbar_k)``, ``xbar_{k+1} =
  Ad xhat_{k|k} + Bd u_k``;
* predictor (one sample of delay): ``xhat_{k+1|k} = Ad xhat_{k|k-1} + Bd u_k + L (m_k - Cm
  xhat_{k|k-1})``.

Refused before anything is solved, each a ``ValueError`` naming what is wrong (the modes with
their frequency in Hz and the sample time; ``hubbeam.control.sampling``): a measurement
covariance that is not positive definite, a process-noise variance below zero, a design-model
mode above half the sampling frequency, a mode that the signals cannot see and that does not
decay, a mode lost by pathological sampling, and a mode on the unit circle (the free hub's
rigid-body mode, undamped vibration modes) that the process noise leaves undisturbed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from hubbeam.control.sampling import (
    measurement_rows,
    nyquist_check,
    observability_check,
    reachability_check,
)
from hubbeam.linear.discrete import hold_matrices

#: the forms of the filter
FORMS = ("current", "predictor")


@dataclass(frozen=True, eq=False)
class KalmanFilter:
    """The steady-state filter of ``model`` (module docstring): the ``sensors`` and their rows
    ``Cm``, the noise ``G``, ``Qw``, ``Rv``, the gains ``L`` (predictor) and ``M`` (current
    estimate), the a-priori covariance ``P`` and the a-posteriori one ``P_posterior``, the
    estimation-error poles ``eig(Ad - L Cm)`` and the ``form`` the controller uses."""

    model: object
    sensors: tuple
    Cm: np.ndarray
    G: np.ndarray
    Qw: np.ndarray
    Rv: np.ndarray
    L: np.ndarray
    M: np.ndarray
    P: np.ndarray
    P_posterior: np.ndarray
    poles: np.ndarray
    form: str


def _variance(value, argument: str) -> float:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0.0):
        raise ValueError(f"{argument} = {value!r}; allowed: a variance >= 0 (process noise positive semidefinite)")
    return float(value)


def process_noise(dm, input_noise: float = 0.0, state_noise: Mapping[str, float] | None = None):
    """``(G, Qw)`` of the process noise (module docstring), checked: variances ``>= 0``, states of
    the plant by name."""
    columns, variances = [], []
    if input_noise:
        n, m = dm.plant_states, len(dm.inputs)
        gamma = np.zeros((dm.A.shape[0], m))
        gamma[:n] = hold_matrices(dm.continuous.A, dm.continuous.B, dm.Ts)[1]
        columns.append(gamma)
        variances += [_variance(input_noise, "input_noise")] * m
    else:
        _variance(input_noise, "input_noise")
    plant = dm.states[:dm.plant_states]
    for name, value in (state_noise or {}).items():
        if name not in plant:
            raise ValueError(f"state_noise.{name}: unknown name; allowed: the plant's states {', '.join(plant)}")
        column = np.zeros((dm.A.shape[0], 1))
        column[plant.index(name)] = 1.0
        columns.append(column)
        variances.append(_variance(value, f"state_noise.{name}"))
    G = np.hstack(columns) if columns else np.zeros((dm.A.shape[0], 0))
    return G, np.diag(variances)


def measurement_noise(sensors, covariance=None) -> np.ndarray:
    """``Rv``: the sensors' variances on the diagonal, or ``covariance`` (p, p); ``ValueError``
    unless symmetric and positive definite (its smallest eigenvalue, or the sensor with variance 0,
    named)."""
    p = len(sensors)
    if covariance is None:
        Rv = np.diag([sensor.variance for sensor in sensors])
        for j, sensor in enumerate(sensors):
            if not sensor.variance > 0.0:
                raise ValueError(f"sensors[{j}] ({sensor.signal}): noise variance noise^2 + quantum^2 / 12 = "
                                 f"{sensor.variance!r}; allowed: > 0 (the measurement covariance must be positive "
                                 "definite)")
        return Rv
    Rv = np.asarray(covariance, dtype=float)
    if Rv.shape != (p, p) or not np.all(np.isfinite(Rv)) or not np.allclose(Rv, Rv.T, rtol=1e-12, atol=0.0):
        raise ValueError(f"measurement_covariance of shape {Rv.shape}; allowed: a finite symmetric ({p}, {p}) matrix")
    smallest = float(np.linalg.eigvalsh(Rv)[0])
    if not smallest > 0.0:
        raise ValueError(f"measurement_covariance has the eigenvalue {smallest:.6g}; allowed: a positive definite "
                         "matrix")
    return Rv


def kalman_filter(dm, sensors, input_noise: float = 0.0, state_noise: Mapping[str, float] | None = None,
                  measurement_covariance=None, form: str = "current") -> KalmanFilter:
    """The steady-state Kalman filter of the discrete model ``dm`` measured by ``sensors``
    (:class:`hubbeam.model.maneuvers.SensorSpec`), every argument checked first (module docstring)."""
    import control as ct

    if form not in FORMS:
        raise ValueError(f"form = {form!r}; allowed: one of {', '.join(FORMS)}")
    sensors = tuple(sensors)
    if not sensors:
        raise ValueError("sensors = (); allowed: at least one measured signal")
    Cm = measurement_rows(dm, sensors)
    Rv = measurement_noise(sensors, measurement_covariance)
    G, Qw = process_noise(dm, input_noise, state_noise)
    what = f"the Kalman filter of {dm.continuous.name}"
    nyquist_check(dm, what)
    observability_check(dm, Cm, what)
    reachability_check(dm, G @ np.sqrt(Qw), what, "the process noise (estimator.input_noise, estimator.state_noise)",
                       unit_circle_only=True)
    L, P, poles = ct.dlqe(dm.A, G, Cm, Qw, Rv)
    P = np.asarray(P)
    M = P @ Cm.T @ np.linalg.inv(Cm @ P @ Cm.T + Rv)
    return KalmanFilter(model=dm, sensors=sensors, Cm=Cm, G=G, Qw=Qw, Rv=Rv, L=np.asarray(L), M=M, P=P,
                        P_posterior=(np.eye(P.shape[0]) - M @ Cm) @ P, poles=np.asarray(poles), form=form)


__all__ = ["FORMS", "KalmanFilter", "kalman_filter", "measurement_noise", "process_noise"]
