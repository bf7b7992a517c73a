"""Hub maneuvers: one record per kind, holding everything hubbeam knows about that kind.

A case's ``maneuver`` (checked with the configuration: schema ``maneuver``, one branch of keys per
kind) becomes one of the frozen records below (:func:`maneuver_from_dict`; the reference motion of
a controller, :func:`reference_from_dict`). Each record states its ``kind``, whether the hub is
``prescribed`` (its motion given, the torque that drives it an output) or ``free`` (the applied
torque enters the hub row of Eq. 24), its fields (the schema's keys of that kind,
``tests/test_maneuvers.py`` holds the two equal), and answers every question the rest of hubbeam
asks of a maneuver:

* :meth:`~Maneuver.kernel_parameters`: the kernel's integer kind and float array ``mp``
  (:mod:`hubbeam.core.maneuver`; the splines' coefficients computed here once per run with scipy's
  ``CubicSpline``, ``bc_type="clamped"``);
* :meth:`~Maneuver.stops`: the times where the forcing is not smooth, which no step may cross;
* :meth:`~Maneuver.start_speed`: a prescribed hub's speed at ``t = 0`` (None for a free hub);
* :meth:`~Maneuver.highest_speed`: the highest hub speed reached by ``t_end`` (the derived grid
  of the eigen-analysis, ``hubbeam.configuration.defaults``);
* :attr:`~Maneuver.end`: when the hub input stops changing (residual vibration is measured after it).

The kinds:

* ``prescribed`` :class:`SpinUp` ``{wf, tf}``: the spin-up of Eq. (43); also a reference motion;
* ``torque`` :class:`TorquePulse` ``{tau_max, tf}``: the torque pulse of Eq. (44) on a free hub;
* ``speed_table`` :class:`SpeedTable` ``{time, speed}`` (s, rad s-1): a prescribed hub speed, a
  clamped cubic spline with zero slope at both ends (theta its exact integral from theta(0) = 0),
  the first speed held before the table and the last after it;
* ``torque_table`` :class:`TorqueTable` ``{time, torque}`` (s, N m): the torque on a free hub,
  linear between the rows, the first value held before the table and the last after it;
* ``pd`` :class:`PdControl` ``{kp, kd, reference}``: a free hub under ``tau = kp (theta_r - theta)
  + kd (theta_r' - theta')`` tracking a reference motion: :class:`SpinUp` or ``angle_table``
  :class:`AngleTable` ``{time, angle}`` (clamped cubic spline as above);
* ``state_feedback`` :class:`StateFeedback` ``{reference, feedforward, gains | output_feedback |
  design}``: a free hub under feedback of its whole state; its resolved gains, the stretch of the
  reference and the feedforward inertia are a :class:`FeedbackLaw`, which
  ``hubbeam.control.feedback`` resolves from the case (a design needs the linear models).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any, ClassVar, NamedTuple

import numpy as np
from scipy.interpolate import CubicSpline

from hubbeam.core import maneuver as kernels
from hubbeam.core import sampled as sampled_kernels
from hubbeam.model.frozen import FrozenMap, freeze, thaw

#: hub conditions: the motion given (the torque an output), or the torque given (the motion free)
PRESCRIBED_HUB = "prescribed"
FREE_HUB = "free"
#: points per time span on which the rigid hub speed of a torque table is integrated
_TORQUE_TABLE_POINTS = 4001


class FeedbackLaw(NamedTuple):
    """The resolved gains of a ``state_feedback`` maneuver in the coordinates ``x = (y, y')``,
    ``y = (theta, q1, q2)`` of the simulated model (``2 N`` gains, positions then rates; zero on
    the ``q1`` of a model that keeps none), the ``q1`` reference per squared reference speed
    ``stretch`` (``n`` values), the feedforward on the reference's acceleration ``inertia`` and on
    its rate ``damping`` (0: none; with a drive both are divided by its torque gain)."""

    gains: np.ndarray
    stretch: np.ndarray
    inertia: float
    damping: float = 0.0


def packed_table(time, values, interpolation: str) -> np.ndarray:
    """The table layout of :mod:`hubbeam.core.maneuver`: ``[m, t, I, c (per interval), last]``.

    ``interpolation`` is ``"spline"`` (clamped cubic spline, zero slope at both ends) or
    ``"linear"``; ``I_k`` is the exact integral of the interpolant from 0 (the first value held
    before ``t_0``) to ``t_k``.
    """
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float)
    h = np.diff(t)
    if interpolation == "spline":
        coefficients = CubicSpline(t, y, bc_type="clamped").c[::-1].T  # rows (c0, c1, c2, c3)
    else:
        slope = np.diff(y) / h
        coefficients = np.column_stack([y[:-1], slope, np.zeros_like(h), np.zeros_like(h)])
    c0, c1, c2, c3 = coefficients.T
    pieces = h * (c0 + h * (c1 / 2.0 + h * (c2 / 3.0 + h * c3 / 4.0)))
    integrals = y[0] * t[0] + np.concatenate([[0.0], np.cumsum(pieces)])
    return np.concatenate([[t.size], t, integrals, coefficients.ravel(), [y[-1]]])


@dataclass(frozen=True)
class Record:
    """What every maneuver and reference record shares: built from its checked mapping (the
    schema's keys of its kind), written back as one."""

    kind: ClassVar[str]

    @classmethod
    def from_dict(cls, entry) -> Record:
        """The record of a checked mapping of this kind (numbers as floats, lists as tuples)."""
        values = {}
        for item in fields(cls):
            if item.name in entry:
                values[item.name] = _field_value(cls, item.name, entry[item.name])
        return cls(**values)

    def to_dict(self) -> dict:
        """``{"kind": ..., key: value, ...}`` with lists for tables, as written in a configuration
        (keys left at None are left out)."""
        plain = {item.name: thaw(_plain(getattr(self, item.name))) for item in fields(self)}
        return {"kind": self.kind} | {key: value for key, value in plain.items() if value is not None}


def _field_value(cls, name: str, value: Any) -> Any:
    if name in NESTED:
        return NESTED[name](value)
    if isinstance(value, (list, tuple)):
        return tuple(float(item) for item in value)
    if isinstance(value, (bool, str)) or value is None:
        return value
    if isinstance(value, dict | FrozenMap):
        return freeze({key: float(item) for key, item in value.items()})
    return float(value)


def _plain(value: Any) -> Any:
    return value.to_dict() if hasattr(value, "to_dict") else value


class Maneuver(Record):
    """A hub maneuver (module docstring); subclasses state ``kind`` and ``hub``; ``needs_drive``:
    its command is a voltage, for a case with a drive only; ``takes_drive``: its command may be
    given through a drive (a controller's output in volts); an open-loop torque may not."""

    hub: ClassVar[str]
    needs_drive: ClassVar[bool] = False
    takes_drive: ClassVar[bool] = True

    def kernel_parameters(self, law: FeedbackLaw | None = None) -> tuple[int, np.ndarray]:
        raise NotImplementedError

    def stops(self) -> np.ndarray:
        raise NotImplementedError

    def start_speed(self) -> float | None:
        """The hub speed at ``t = 0`` (rad s-1) of a prescribed hub; None for a free hub."""
        if self.hub != PRESCRIBED_HUB:
            return None
        code, mp = self.kernel_parameters()
        return float(kernels.prescribed_motion(code, 0.0, mp)[1])

    def highest_speed(self, t_end: float, inertia: float, drive=None) -> float:
        """The highest hub speed (rad s-1) the maneuver reaches by ``t_end``, a free hub taken as
        rigid of ``inertia`` (kg m2), driven through ``drive`` (a ``DcMotor``) where it has one."""
        raise NotImplementedError

    @property
    def end(self) -> float:
        """When the hub input stops changing, s."""
        raise NotImplementedError

    @property
    def final_speed(self) -> float:
        """The hub speed the command ends at, rad s-1 (0: at rest, or not known beforehand, as after
        a torque)."""
        return 0.0

    @property
    def needs_law(self) -> bool:
        """The kernel parameters need a :class:`FeedbackLaw` resolved for the run's matrices."""
        return False


@dataclass(frozen=True)
class SpinUp(Maneuver):
    """The spin-up of Eq. (43) with the factor ``t`` the transcription lost (reproduction note 1):
    the hub speed rises from 0 to ``wf`` (rad s-1) over ``tf`` (s), then holds. As a maneuver the
    hub is prescribed; as the reference of a controller it gives the angle, rate and acceleration."""

    kind: ClassVar[str] = "prescribed"
    hub: ClassVar[str] = PRESCRIBED_HUB
    code: ClassVar[int] = kernels.PRESCRIBED
    #: the parameters in the order of the kernel's ``mp`` (a sweep may span them)
    kernel_keys: ClassVar[tuple[str, ...]] = ("wf", "tf")
    #: a reference motion whose acceleration is known, so a rigid feedforward may use it
    gives_acceleration: ClassVar[bool] = True
    wf: float
    tf: float

    def kernel_parameters(self, law=None):
        return self.code, np.array([getattr(self, key) for key in self.kernel_keys])

    def stops(self):
        return np.array([self.tf])

    def highest_speed(self, t_end, inertia, drive=None):
        return self.wf  # Eq. 43 rises monotonically to it

    @property
    def end(self):
        return self.tf

    @property
    def final_speed(self) -> float:
        """The speed the motion ends at, rad s-1."""
        return self.wf


@dataclass(frozen=True)
class TorquePulse(Maneuver):
    """The rest-to-rest torque pulse of Eq. (44), ``tau_max sin(2 pi t / tf)`` for ``0 <= t <= tf``
    (note 8), on a free hub."""

    kind: ClassVar[str] = "torque"
    hub: ClassVar[str] = FREE_HUB
    code: ClassVar[int] = kernels.TORQUE
    takes_drive: ClassVar[bool] = False
    kernel_keys: ClassVar[tuple[str, ...]] = ("tau_max", "tf")
    tau_max: float
    tf: float

    def kernel_parameters(self, law=None):
        return self.code, np.array([getattr(self, key) for key in self.kernel_keys])

    def stops(self):
        return np.array([self.tf])

    def highest_speed(self, t_end, inertia, drive=None):
        """A rigid hub of ``inertia`` under the pulse: ``tau_max tf / (pi J)`` at ``tf / 2``."""
        return self.tau_max * self.tf / (math.pi * inertia)

    @property
    def end(self):
        return self.tf


@dataclass(frozen=True)
class Table(Maneuver):
    """A tabulated maneuver or reference: ``time`` (s, strictly increasing from >= 0) and one value
    column, :attr:`column`, interpolated by :attr:`interpolation`."""

    column: ClassVar[str]
    interpolation: ClassVar[str]
    time: tuple[float, ...]

    @property
    def values(self) -> tuple[float, ...]:
        return getattr(self, self.column)

    def kernel_parameters(self, law=None):
        return self.code, packed_table(self.time, self.values, self.interpolation)

    def stops(self):
        return np.asarray(self.time, dtype=float)

    @property
    def end(self):
        return self.time[-1]


@dataclass(frozen=True)
class SpeedTable(Table):
    """A prescribed hub speed from a table (clamped cubic spline, module docstring)."""

    kind: ClassVar[str] = "speed_table"
    hub: ClassVar[str] = PRESCRIBED_HUB
    code: ClassVar[int] = kernels.SPEED_TABLE
    column: ClassVar[str] = "speed"
    interpolation: ClassVar[str] = "spline"
    speed: tuple[float, ...]

    def highest_speed(self, t_end, inertia, drive=None):
        return float(np.max(np.abs(self.speed)))

    @property
    def final_speed(self):
        return self.speed[-1]


@dataclass(frozen=True)
class TorqueTable(Table):
    """The torque on a free hub from a table (linear between the rows, module docstring)."""

    kind: ClassVar[str] = "torque_table"
    hub: ClassVar[str] = FREE_HUB
    code: ClassVar[int] = kernels.TORQUE_TABLE
    takes_drive: ClassVar[bool] = False
    column: ClassVar[str] = "torque"
    interpolation: ClassVar[str] = "linear"
    torque: tuple[float, ...]

    def highest_speed(self, t_end, inertia, drive=None):
        """A rigid hub of ``inertia`` under the table (first value held before it, last after it)
        up to ``t_end``; the torque is linear between the rows, which are nodes of the grid, so the
        trapezoidal rule is exact at every node."""
        t = np.union1d(np.linspace(0.0, t_end, _TORQUE_TABLE_POINTS), [time for time in self.time if time < t_end])
        torque = np.interp(t, self.time, self.torque)
        momentum = np.concatenate([[0.0], np.cumsum(np.diff(t) * (torque[1:] + torque[:-1]) / 2.0)])
        return float(np.max(np.abs(momentum))) / inertia


@dataclass(frozen=True)
class VoltageTable(Table):
    """The voltage the amplifier applies to the hub's drive, from a table (linear between the rows,
    the first value held before the table and the last after it): a case with a ``drive`` only
    (``hubbeam.model.drive``; the kernel's open-loop command is then in volts)."""

    kind: ClassVar[str] = "voltage_table"
    hub: ClassVar[str] = FREE_HUB
    code: ClassVar[int] = kernels.TORQUE_TABLE
    column: ClassVar[str] = "voltage"
    interpolation: ClassVar[str] = "linear"
    needs_drive: ClassVar[bool] = True
    voltage: tuple[float, ...]

    def highest_speed(self, t_end, inertia, drive=None):
        """A rigid hub of ``inertia`` driven by the table through ``drive``: ``J w' = kV V - c w``
        (``torque_gain``, ``hub_damping``; Coulomb friction and the limit left out, which only slow
        it), integrated exactly between the points of a fine grid on which ``V`` is taken linear."""
        t = np.union1d(np.linspace(0.0, t_end, _TORQUE_TABLE_POINTS), [time for time in self.time if time < t_end])
        volts = np.clip(np.interp(t, self.time, self.voltage), -drive.voltage_limit, drive.voltage_limit)
        rate = drive.hub_damping / inertia
        speed, highest = 0.0, 0.0
        for h, v0, v1 in zip(np.diff(t), volts[:-1], volts[1:]):
            decay = math.exp(-rate * h)
            target = drive.torque_gain * 0.5 * (v0 + v1) / drive.hub_damping
            speed = target + (speed - target) * decay
            highest = max(highest, abs(speed))
        return highest


@dataclass(frozen=True)
class AngleTable(Table):
    """A reference hub angle from a table (clamped cubic spline, zero slope at both ends, held
    outside the table): a controller's reference motion only."""

    kind: ClassVar[str] = "angle_table"
    hub: ClassVar[str] = FREE_HUB
    code: ClassVar[int] = kernels.ANGLE_TABLE
    column: ClassVar[str] = "angle"
    interpolation: ClassVar[str] = "spline"
    gives_acceleration: ClassVar[bool] = False
    angle: tuple[float, ...]

    def highest_speed(self, t_end, inertia, drive=None):
        """The steepest mean slope between the rows."""
        return float(np.max(np.abs(np.diff(self.angle) / np.diff(self.time))))

    @property
    def final_speed(self) -> float:
        return 0.0  # the spline's slope is zero at the last row, and the angle held after it


@dataclass(frozen=True)
class Tracking(Maneuver):
    """A free hub under a controller that tracks the ``reference`` motion."""

    hub: ClassVar[str] = FREE_HUB
    reference: SpinUp | AngleTable

    def reference_parameters(self) -> np.ndarray:
        """``[reference kind, reference parameters...]`` as the kernel reads them."""
        code, mp = self.reference.kernel_parameters()
        return np.concatenate([[float(code)], mp])

    def stops(self):
        return self.reference.stops()

    @property
    def final_speed(self):
        return self.reference.final_speed

    def highest_speed(self, t_end, inertia, drive=None):
        return self.reference.highest_speed(t_end, inertia)

    @property
    def end(self):
        return self.reference.end


@dataclass(frozen=True)
class PdControl(Tracking):
    """``tau = kp (theta_r - theta) + kd (theta_r' - theta')`` (N m rad-1, N m s rad-1)."""

    kind: ClassVar[str] = "pd"
    code: ClassVar[int] = kernels.PD
    kp: float
    kd: float

    def kernel_parameters(self, law=None):
        head = [self.kp, self.kd]
        assert len(head) + 1 == kernels.PD_REFERENCE
        return self.code, np.concatenate([head, self.reference_parameters()])


@dataclass(frozen=True)
class LqrDesign:
    """LQR on the linear model of ``model`` at ``speed`` (schema ``lqr_design``): the weights on
    its states or measured signals, the input's weight on the torque (an ideal actuator) or on the
    voltage (a drive), the design's own number of modes (default the case's), and for the
    courseware's ``lumped`` model the held-hub frequency its spring is fitted to (Hz)."""

    model: str
    speed: float
    weights: FrozenMap
    torque_weight: float | None = None
    voltage_weight: float | None = None
    modes: int | None = None
    held_frequency: float | None = None

    @classmethod
    def from_dict(cls, entry) -> LqrDesign:
        optional = {key: (int if key == "modes" else float)(entry[key])
                    for key in ("torque_weight", "voltage_weight", "modes", "held_frequency") if key in entry}
        return cls(model=entry["model"], speed=float(entry["speed"]),
                   weights=freeze({key: float(value) for key, value in entry["weights"].items()}), **optional)

    @property
    def input_weight(self) -> float:
        """The weight ``R`` of the input: the torque's or the voltage's, whichever is given."""
        return self.torque_weight if self.voltage_weight is None else self.voltage_weight

    def to_dict(self) -> dict:
        plain = {"model": self.model, "speed": self.speed, "weights": thaw(self.weights)}
        return plain | {item.name: getattr(self, item.name) for item in fields(self)
                        if item.name not in plain and getattr(self, item.name) is not None}


#: quantisation modes of a sensor: the kernel's codes (``hubbeam.core.sampled``)
QUANTISATION_MODES = {"round": sampled_kernels.ROUND, "edges": sampled_kernels.EDGES}


@dataclass(frozen=True)
class SensorSpec:
    """A sensor (schema ``sensor``), the one record the configuration, the sampled designs and the
    simulated loop share: the reading ``s = gain y + offset`` of the measured ``signal`` ``y`` (a
    linear model's output without feedthrough, or a state the controller reads exactly), passed
    through an analog first-order low-pass of time constant ``lowpass`` (s; 0: none), with white
    noise of standard deviation ``noise`` and the quantisation step ``quantum`` (0: none), ``mode``
    ``round`` (to the nearest step) or ``edges`` (an incremental encoder counting edges: the step
    below), both in the sensor's unit ``unit`` (UDUNITS; empty: the signal's). The kernel reads
    the sensors of a loop packed as arrays (``hubbeam.simulation.sampled.loop_arrays``)."""

    signal: str
    gain: float = 1.0
    offset: float = 0.0
    noise: float = 0.0
    lowpass: float = 0.0
    quantum: float = 0.0
    mode: str = "round"
    unit: str = ""

    @classmethod
    def from_dict(cls, entry) -> SensorSpec:
        text = ("signal", "mode", "unit")
        return cls(**{key: value if key in text else float(value) for key, value in entry.items()})

    def to_dict(self) -> dict:
        """The sensor's keys, ``unit`` only when given (a configuration's sensor has none)."""
        return {item.name: getattr(self, item.name) for item in fields(self) if item.name != "unit" or self.unit}

    @property
    def variance(self) -> float:
        """``noise^2 + quantum^2 / 12``: the noise variance an estimator assumes (the quantisation
        error uniform over one step), sensor units^2."""
        return self.noise**2 + self.quantum**2 / 12.0

    def problem(self) -> tuple[str, object, str] | None:
        """The first field that no sensor may hold, as ``(field, value, allowed)``, or None: a
        non-empty ``signal``, a finite non-zero ``gain``, a finite ``offset``, ``noise``, ``lowpass``
        and ``quantum`` finite and >= 0, ``mode`` one of :data:`QUANTISATION_MODES`."""
        if not (isinstance(self.signal, str) and self.signal):
            return "signal", self.signal, "a non-empty name"
        for key in ("gain", "offset", "noise", "lowpass", "quantum"):
            value = getattr(self, key)
            number = isinstance(value, (int, float, np.floating, np.integer)) and not isinstance(value, bool)
            if not (number and math.isfinite(value)) or (key == "gain" and value == 0.0) or (
                    key not in ("gain", "offset") and value < 0.0):
                return key, value, ("a finite, non-zero number" if key == "gain" else "a finite number"
                                    if key == "offset" else "a finite number >= 0 (0: none)")
        if self.mode not in QUANTISATION_MODES:
            return "mode", self.mode, f"one of {', '.join(QUANTISATION_MODES)}"
        return None


@dataclass(frozen=True)
class Estimator:
    """How a sampled controller gets the state its gains act on (schema ``estimator``): ``exact``
    (the design's states read without error: a bound), ``filtered_differences`` (the measured
    angles and their rates from first-order filtered differences of cut-off ``cutoff``, rad s-1,
    as the Quanser courseware does) or ``kalman`` (a steady-state Kalman filter in the ``current``
    or ``predictor`` form, with the process noise ``input_noise`` on the input and ``state_noise``
    on named states, the sensors' noise and quantisation as its measurement noise)."""

    kind: str
    cutoff: float | None = None
    form: str | None = None
    input_noise: float | None = None
    state_noise: FrozenMap | None = None

    @classmethod
    def from_dict(cls, entry) -> Estimator:
        values = {key: value if key in ("kind", "form") else float(value)
                  for key, value in entry.items() if key != "state_noise"}
        if "state_noise" in entry:
            values["state_noise"] = freeze({key: float(value) for key, value in entry["state_noise"].items()})
        return cls(**values)

    def to_dict(self) -> dict:
        return {item.name: thaw(getattr(self, item.name)) for item in fields(self)
                if getattr(self, item.name) is not None}


@dataclass(frozen=True)
class Sampling:
    """A state feedback run as a sampled digital controller (schema ``sampling``): the sample time
    (s), the computation delay in samples (whole or fractional), the gain (``discrete``: LQR
    redesigned on the zero-order-hold model; ``continuous``: the continuous LQR gain applied
    through the hold), whether to design on the design model truncated below half the sampling
    frequency (``reduce``), the estimator, the sensors and the seed of their noise."""

    sample_time: float
    delay: float = 0.0
    gain: str = "discrete"
    reduce: bool = False
    estimator: Estimator = Estimator("exact")
    sensors: tuple[SensorSpec, ...] = ()
    seed: int = 0

    @classmethod
    def from_dict(cls, entry) -> Sampling:
        values = {"sample_time": float(entry["sample_time"])}
        if "delay" in entry:
            values["delay"] = float(entry["delay"])
        if "gain" in entry:
            values["gain"] = entry["gain"]
        if "reduce" in entry:
            values["reduce"] = bool(entry["reduce"])
        if "estimator" in entry:
            values["estimator"] = Estimator.from_dict(entry["estimator"])
        if "sensors" in entry:
            values["sensors"] = tuple(SensorSpec.from_dict(sensor) for sensor in entry["sensors"])
        if "seed" in entry:
            values["seed"] = int(entry["seed"])
        return cls(**values)

    def to_dict(self) -> dict:
        """The settings as a configuration writes them; ``sensors`` only when there are any (the exact
        estimator reads the design's states, and the schema takes no empty list)."""
        plain = {"sample_time": self.sample_time, "delay": self.delay, "gain": self.gain, "reduce": self.reduce,
                 "estimator": self.estimator.to_dict()}
        if self.sensors:
            plain["sensors"] = [sensor.to_dict() for sensor in self.sensors]
        return plain | {"seed": self.seed}


@dataclass(frozen=True)
class StateFeedback(Tracking):
    """``tau = J theta_r'' - K (x - x_r)`` on the whole state, with ``K`` given by state name
    (``gains``), from gains on measured signals (``output_feedback``) or designed (``design``):
    exactly one of the three (``hubbeam.control.feedback``)."""

    kind: ClassVar[str] = "state_feedback"
    code: ClassVar[int] = kernels.STATE_FEEDBACK
    feedforward: bool = False
    gains: FrozenMap | None = None
    output_feedback: FrozenMap | None = None
    design: LqrDesign | None = None
    #: the law run as a sampled digital controller (None: continuously)
    sampling: Sampling | None = None

    @property
    def needs_law(self):
        return True

    def kernel_parameters(self, law=None):
        if law is None:
            raise ValueError("maneuver.kind = 'state_feedback' without its feedback law; allowed: "
                             "hubbeam.control.cases.simulate_case, which resolves the gains")
        head = [float(law.gains.size // 2), float(law.inertia), float(law.damping)]
        assert len(head) == kernels.FEEDBACK_GAINS
        return self.code, np.concatenate([head, law.gains, law.stretch, self.reference_parameters()])

    def to_dict(self):
        plain = super().to_dict()
        if not self.feedforward:
            del plain["feedforward"]
        return plain


#: the maneuver kinds by name (schema ``maneuver``)
MANEUVERS: dict[str, type[Maneuver]] = {record.kind: record for record in (
    SpinUp, TorquePulse, SpeedTable, TorqueTable, VoltageTable, PdControl, StateFeedback)}
#: the kinds of a controller's reference motion by name (schema ``reference``)
REFERENCES: dict[str, type[Maneuver]] = {record.kind: record for record in (SpinUp, AngleTable)}
#: the tabulated kinds, maneuvers and references, by name: their columns (``hubbeam.configuration.tabular``)
TABLES: dict[str, type[Table]] = {kind: record for kind, record in (MANEUVERS | REFERENCES).items()
                                  if issubclass(record, Table)}


#: the fields that hold records of their own, and their builders
NESTED = {"reference": lambda entry: reference_from_dict(entry), "design": LqrDesign.from_dict,
          "sampling": Sampling.from_dict}


def maneuver_from_dict(entry) -> Maneuver:
    """The record of a checked ``maneuver`` mapping (a :class:`Maneuver` is returned as it is)."""
    if isinstance(entry, Maneuver):
        return entry
    return MANEUVERS[entry["kind"]].from_dict(entry)


def reference_from_dict(entry) -> SpinUp | AngleTable:
    """The record of a checked ``reference`` mapping."""
    if isinstance(entry, Maneuver):
        return entry
    return REFERENCES[entry["kind"]].from_dict(entry)
