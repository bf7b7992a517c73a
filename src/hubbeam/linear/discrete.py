"""Discrete-time models: a linear model sampled with a zero-order hold and an input delay.

A controller computes the command ``u_k`` at ``t_k = k Ts`` from the samples at ``t_k``; the hold
applies it to the plant from ``t_k + D Ts`` until ``t_{k+1} + D Ts`` (the convention of the sampled
loop, ``docs/rig-design.md``). With ``D = d + f`` (``d`` whole samples, ``0 <= f < 1``) the input
over ``[t_k, t_{k+1})`` is ``u_{k-d-1}`` until ``t_k + f Ts`` and ``u_{k-d}`` after it, so
(Franklin, Powell and Workman, *Digital Control of Dynamic Systems*, 3rd ed., 1998, Sec. 4.3.4)

    x_{k+1} = Phi x_k + Gamma_0 u_{k-d} + Gamma_1 u_{k-d-1},
    Phi = exp(A Ts),   Gamma(tau) = int_0^tau exp(A s) ds B,
    Gamma_0 = Gamma((1 - f) Ts),   Gamma_1 = exp(A (1 - f) Ts) Gamma(f Ts),

``Gamma_0 + Gamma_1 = Gamma(Ts)``. ``exp`` and ``Gamma`` come from one matrix exponential of
``[[A, B], [0, 0]] tau`` (Van Loan, 1978). The delayed inputs become states: the model holds the
``m = d + (1 if f > 0 else 0)`` past commands ``u_{k-1} .. u_{k-m}`` (named ``<input>_lag<j>``,
in the input's unit) after the plant's states, shifted by one place each sample, the newest fed by
``u_k``. With ``D = 0`` this is python-control's ``sample_system(..., method="zoh")``.

The outputs are sampled at ``t_k``, with the input that acts just after ``t_k`` in a feedthrough
(the accelerometer's): ``D`` itself without delay, else the lag state that holds that input.

:func:`discretise` returns a :class:`DiscreteModel` (``A, B, C, D``, named states, inputs and
outputs, ``Ts``, ``delay``; :meth:`DiscreteModel.to_control` a python-control system with
``dt = Ts``); ``hubbeam.linear.export`` writes it like the continuous models.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg


@dataclass(frozen=True, eq=False)
class DiscreteModel:
    """``x_{k+1} = A x_k + B u_k``, ``y_k = C x_k + D u_k`` of ``continuous`` sampled every ``Ts``
    seconds with the input delayed by ``delay`` samples (module docstring). The first
    ``continuous.A.shape[0]`` states are the plant's, the rest the delayed inputs."""

    continuous: object
    Ts: float
    delay: float
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]

    @property
    def model(self) -> str:
        """The continuous model's name of the model (``FOAM``, ...)."""
        return self.continuous.model

    @property
    def speed(self) -> float:
        """The continuous model's operating speed, rad s-1."""
        return self.continuous.speed

    @property
    def plant_states(self) -> int:
        """The number of the plant's states (the continuous model's)."""
        return self.continuous.A.shape[0]

    @property
    def lags(self) -> int:
        """The number of past commands held as states, per input."""
        return (self.A.shape[0] - self.plant_states) // max(len(self.inputs), 1)

    @property
    def name(self) -> str:
        """The continuous model's name with the sample time and the delay (``p`` for the point)."""
        def text(value):
            return f"{value:.10g}".replace(".", "p").replace("+", "").replace("-", "m")
        return f"{self.continuous.name}_Ts{text(self.Ts)}s_delay{text(self.delay)}"

    def to_control(self):
        """The model as a discrete :class:`control.StateSpace` (``dt = Ts``) with its names."""
        import control as ct

        return ct.ss(self.A, self.B, self.C, self.D, dt=self.Ts, states=list(self.states),
                     inputs=list(self.inputs), outputs=list(self.outputs), name=self.name)


def check_sampling(Ts, delay) -> tuple[float, float]:
    """``(Ts, delay)`` as floats; ``ValueError`` unless ``Ts > 0`` (s) and ``delay >= 0`` (samples),
    both finite."""
    def number(value):
        return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)

    if not (number(Ts) and math.isfinite(Ts) and Ts > 0.0):
        raise ValueError(f"Ts = {Ts!r}; allowed: a finite sample time > 0 s")
    if not (number(delay) and math.isfinite(delay) and delay >= 0.0):
        raise ValueError(f"delay = {delay!r}; allowed: a finite input delay >= 0 samples")
    return float(Ts), float(delay)


def hold_matrices(A: np.ndarray, B: np.ndarray, tau: float) -> tuple[np.ndarray, np.ndarray]:
    """``(exp(A tau), Gamma(tau))``, ``Gamma(tau) = int_0^tau exp(A s) ds B``, from the exponential of
    ``[[A, B], [0, 0]] tau``."""
    n, m = B.shape
    block = np.zeros((n + m, n + m))
    block[:n, :n], block[:n, n:] = A, B
    E = scipy.linalg.expm(block * tau)
    return E[:n, :n], E[:n, n:]


def discretise(model, Ts: float, delay: float = 0.0) -> DiscreteModel:
    """The zero-order-hold model of ``model`` (anything with ``A, B, C, D``, ``states``, ``inputs``,
    ``outputs`` and ``name``: a :class:`~hubbeam.linear.statespace.LinearModel`) at the sample time
    ``Ts`` (s) with the input delayed by ``delay`` samples, whole or fractional (module docstring)."""
    Ts, delay = check_sampling(Ts, delay)
    A, B, C, D = (np.asarray(getattr(model, name), dtype=float) for name in "ABCD")
    n, m = B.shape
    d = math.floor(delay)
    f = delay - d
    lags = d + (1 if f > 0.0 else 0)
    Phi, _ = hold_matrices(A, B, Ts)
    if f > 0.0:
        E0, gamma0 = hold_matrices(A, B, (1.0 - f) * Ts)
        gamma1 = E0 @ hold_matrices(A, B, f * Ts)[1]
    else:
        gamma0, gamma1 = hold_matrices(A, B, Ts)[1], np.zeros((n, m))
    size = n + lags * m
    Ad, Bd = np.zeros((size, size)), np.zeros((size, m))
    Cd, Dd = np.zeros((C.shape[0], size)), np.zeros_like(D)
    Ad[:n, :n], Cd[:, :n] = Phi, C

    def lag(j):  # the columns of u_{k-j}, j >= 1
        return slice(n + (j - 1) * m, n + j * m)

    for j, gamma in ((d, gamma0), (d + 1, gamma1)):
        if j == 0:
            Bd[:n] += gamma
        elif j <= lags:
            Ad[:n, lag(j)] += gamma
    if lags:
        Bd[lag(1)] = np.eye(m)
        for j in range(2, lags + 1):
            Ad[lag(j), lag(j - 1)] = np.eye(m)
    acting = d + 1 if f > 0.0 else d  # the input acting just after t_k is u_{k - acting}
    if acting == 0:
        Dd = D.copy()
    else:
        Cd[:, lag(acting)] += D
    states = tuple(model.states) + tuple(f"{name}_lag{j}" for j in range(1, lags + 1) for name in model.inputs)
    return DiscreteModel(continuous=model, Ts=Ts, delay=delay, A=Ad, B=Bd, C=Cd, D=Dd, states=states,
                         inputs=tuple(model.inputs), outputs=tuple(model.outputs))


__all__ = ["DiscreteModel", "check_sampling", "discretise", "hold_matrices"]
