"""The three kinds of experiment a rig gives, each a frozen record read from (and written to) a file.

* :class:`ModalTest`: natural frequencies (Hz), one row per mode, with optional damping ratios (or
  logarithmic decrements, ``zeta = delta / sqrt(4 pi^2 + delta^2)``), the hub ``held`` (a tap test,
  the courseware's free oscillation) or ``free``. Columns ``mode [1]``, ``frequency [Hz]``; optional
  ``damping_ratio [1]`` or ``log_decrement [1]``, ``frequency_std [Hz]``, ``damping_ratio_std [1]``.
* :class:`FrequencyResponse`: from the input ``voltage`` (V, through the drive) or ``hub_torque``
  (N m) to one output of ``hubbeam.linear.statespace.OUTPUTS`` (``hub_angle``,
  ``deflection_angle``, ``tip_deflection``, ``tip_acceleration``). Columns ``frequency [Hz]``, then
  ``magnitude [<output unit> <input unit>-1]`` (or ``[dB]``, 20 log10 of it) and ``phase [deg]``
  (or ``[rad]``), or ``real`` and ``imag`` in the ratio's unit; optional ``coherence [1]``.
* :class:`TimeSeries`: ``time [s]`` (equally spaced), the input column (``voltage [V]`` or
  ``hub_torque [N m]``) and the measured signals in their units, taken open loop (a pulse, a step,
  a swept sine) or inside a known proportional or PD loop on the hub angle: then the record's
  ``loop`` (:class:`PdLoop`, gains in the input's unit per rad and per rad s-1) and a ``reference
  [rad]`` column (the loop's hub-angle reference; the input column is then optional, the command
  the loop computed). Each signal's sensor is a :class:`hubbeam.model.maneuvers.SensorSpec`, as a
  sampled loop's (``simulation/sampled.py``): ``reading = gain x signal + offset``, white noise,
  quantisation (``round`` or counting ``edges``), an analog first-order low-pass. The input's
  samples reach the hub through a ``hold``: ``linear`` between them (hubbeam's tables) or a DAC's
  ``zero_order`` hold, which adds half a sample of delay.

The standard error of a frequency response estimated from ``n_d`` averages with coherence
``gamma^2`` is ``sqrt(1 - gamma^2) / (|gamma| sqrt(2 n_d))``, for ``ln |H|`` and for the phase in
radians alike (Bendat and Piersol, *Random Data*, 4th ed., 2010, Sec. 9.2.4, Table 9.6);
:meth:`FrequencyResponse.standard_error` gives it. A response estimated from a sampled input
holds the hold's own response (``FrequencyResponse.hold``, :meth:`FrequencyResponse.hold_response`;
Franklin, Powell and Workman, *Digital Control of Dynamic Systems*, 1998, Sec. 6.2). Files are read by
:mod:`hubbeam.identification.files`; every refusal names the file, the line, the column and what is
allowed, and a record built in Python is checked the same way (naming the record and its field).
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar

import numpy as np

from hubbeam.identification.files import (
    ColumnSpec,
    ExperimentError,
    check_increasing,
    check_range,
    read_columns,
    uniform_step,
    write_columns,
)
from hubbeam.linear.statespace import INPUT_UNITS, OUTPUTS
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.maneuvers import SensorSpec
from hubbeam.simulation.sampled import QUANTISATION_MODES

#: the inputs an experiment may drive the hub with
INPUTS = ("voltage", "hub_torque")
#: the signals an experiment may measure (a subset of the linear models' outputs)
SIGNALS = ("hub_angle", "deflection_angle", "tip_deflection", "tip_acceleration")
#: hub conditions of a modal test
HUBS = ("held", "free")
#: how a time series was excited (a record of the test; the prediction follows the input column)
EXCITATIONS = ("pulse", "step", "swept_sine", "random")
#: how the samples of a time series's input reached the hub between the samples: ``linear`` (a
#: first-order hold, hubbeam's ``voltage_table``) or ``zero_order`` (a DAC holding each sample)
HOLDS = ("linear", "zero_order")
#: relative standard uncertainties of a modal test's frequencies and damping ratios when the file
#: gives none (only their ratio moves the fitted values: the fit estimates the residuals' scale)
FREQUENCY_UNCERTAINTY = 0.005
DAMPING_UNCERTAINTY = 0.1
#: the smallest standard error of a frequency response's point (coherence 1 would weigh it infinitely)
MIN_RESPONSE_ERROR = 1e-4
#: the least rows of each kind of file
MIN_ROWS = {"modal": 1, "frequency_response": 3, "time_series": 10}
#: the names of experiments (variables of the fit's dataset are named after them)
NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


def _exponents(unit: str) -> list[tuple[str, int]]:
    return [(base, int(power or 1)) for base, power in re.findall(r"([A-Za-z]+)(-?\d+)?", unit)]


def ratio_unit(output: str, input: str) -> str:
    """The unit of a frequency response from ``input`` to ``output``: ``"m s-2 V-1"``, ``"rad N-1 m-1"``."""
    terms = _exponents(OUTPUTS[output][0]) + [(base, -power) for base, power in _exponents(INPUT_UNITS[input])]
    return " ".join(base if power == 1 else f"{base}{power}" for base, power in terms)


def _fail(where: str, value, allowed: str):
    raise ExperimentError(f"{where} = {value!r}; allowed: {allowed}")


def _check_name(name) -> str:
    if not isinstance(name, str) or not NAME.match(name):
        _fail("experiment name", name, "letters, digits and '_', starting with a letter")
    return name


def _vector(where: str, values, size: int | None = None) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim != 1 or (size is not None and array.size != size) or not np.all(np.isfinite(array)):
        _fail(where, np.asarray(values).tolist() if np.size(values) < 8 else f"<{np.shape(values)} values>",
              f"finite numbers, one per row ({size} rows)" if size is not None else "a list of finite numbers")
    return array


@dataclass(frozen=True, eq=False)
class ModalTest:
    """Natural frequencies (Hz) of the listed ``mode`` numbers (1 = the lowest bending mode the
    model predicts for the hub condition) with their standard uncertainties, optional damping
    ratios; ``hub`` ``held`` or ``free``; the hub's steady ``speed`` (rad s-1, 0: at rest)."""

    kind: ClassVar[str] = "modal"
    name: str
    hub: str
    mode: np.ndarray
    frequency: np.ndarray
    frequency_std: np.ndarray | None = None
    damping_ratio: np.ndarray | None = None
    damping_ratio_std: np.ndarray | None = None
    speed: float = 0.0
    source: str = ""

    def __post_init__(self) -> None:
        where = f"experiment {_check_name(self.name)}"
        if self.hub not in HUBS:
            _fail(f"{where}.hub", self.hub, f"one of {', '.join(HUBS)}")
        mode = np.asarray(self.mode)
        if mode.ndim != 1 or mode.size < 1 or not np.all(mode == np.round(mode)) or mode.min() < 1 \
                or np.any(np.diff(mode) <= 0):
            _fail(f"{where}.mode", np.asarray(self.mode).tolist(), "mode numbers 1, 2, ... increasing strictly")
        n = mode.size
        frequency = _vector(f"{where}.frequency", self.frequency, n)
        if frequency.min() <= 0.0 or np.any(np.diff(frequency) <= 0.0):
            _fail(f"{where}.frequency", frequency.tolist(), "frequencies > 0 Hz increasing strictly with the mode")
        std = (FREQUENCY_UNCERTAINTY * frequency if self.frequency_std is None
               else _vector(f"{where}.frequency_std", self.frequency_std, n))
        if std.min() <= 0.0:
            _fail(f"{where}.frequency_std", std.tolist(), "standard uncertainties > 0 Hz")
        values = {"mode": mode.astype(int), "frequency": frequency, "frequency_std": std,
                  "speed": float(self.speed)}
        if not (math.isfinite(values["speed"]) and values["speed"] >= 0.0):
            _fail(f"{where}.speed", self.speed, "a finite hub speed >= 0 rad s-1")
        if self.damping_ratio is not None:
            zeta = _vector(f"{where}.damping_ratio", self.damping_ratio, n)
            if zeta.min() < 0.0 or zeta.max() >= 1.0:
                _fail(f"{where}.damping_ratio", zeta.tolist(), "damping ratios in [0, 1)")
            zeta_std = (np.maximum(DAMPING_UNCERTAINTY * zeta, DAMPING_UNCERTAINTY * 1e-3)
                        if self.damping_ratio_std is None
                        else _vector(f"{where}.damping_ratio_std", self.damping_ratio_std, n))
            if zeta_std.min() <= 0.0:
                _fail(f"{where}.damping_ratio_std", zeta_std.tolist(), "standard uncertainties > 0")
            values |= {"damping_ratio": zeta, "damping_ratio_std": zeta_std}
        elif self.damping_ratio_std is not None:
            _fail(f"{where}.damping_ratio_std", "given", "only with damping ratios")
        for key, value in values.items():
            object.__setattr__(self, key, value)


@dataclass(frozen=True, eq=False)
class FrequencyResponse:
    """The complex ``response`` (output units per input unit) at ``frequency`` (Hz, increasing),
    from ``input`` to ``output``; with the ``coherence`` and the number of ``averages`` of the
    estimate, its standard errors (:meth:`standard_error`)."""

    kind: ClassVar[str] = "frequency_response"
    name: str
    input: str
    output: str
    frequency: np.ndarray
    response: np.ndarray
    coherence: np.ndarray | None = None
    averages: float | None = None
    hold: str | None = None
    sample_time: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        where = f"experiment {_check_name(self.name)}"
        if self.input not in INPUTS:
            _fail(f"{where}.input", self.input, f"one of {', '.join(INPUTS)}")
        if self.hold is not None:
            if self.hold not in HOLDS:
                _fail(f"{where}.hold", self.hold, f"one of {', '.join(HOLDS)}, or none (an analog input)")
            if not (isinstance(self.sample_time, (int, float)) and math.isfinite(self.sample_time)
                    and self.sample_time > 0.0):
                _fail(f"{where}.sample_time", self.sample_time, "the input's sample time > 0 s, required with a hold")
        if self.output not in SIGNALS:
            _fail(f"{where}.output", self.output, f"one of {', '.join(SIGNALS)}")
        frequency = _vector(f"{where}.frequency", self.frequency)
        if frequency.size < MIN_ROWS[self.kind] or frequency.min() <= 0.0 or np.any(np.diff(frequency) <= 0.0):
            _fail(f"{where}.frequency", f"<{frequency.size} values>",
                  f"at least {MIN_ROWS[self.kind]} frequencies > 0 Hz increasing strictly")
        response = np.asarray(self.response, dtype=complex)
        if response.shape != frequency.shape or not np.all(np.isfinite(response)) or np.any(response == 0.0):
            _fail(f"{where}.response", f"<{response.shape} values>", "finite, non-zero values, one per frequency")
        object.__setattr__(self, "frequency", frequency)
        object.__setattr__(self, "response", response)
        if self.coherence is not None:
            coherence = _vector(f"{where}.coherence", self.coherence, frequency.size)
            if coherence.min() < 0.0 or coherence.max() > 1.0:
                _fail(f"{where}.coherence", "values outside [0, 1]", "coherences in [0, 1]")
            averages = self.averages
            if averages is None or not (isinstance(averages, (int, float)) and math.isfinite(averages)
                                        and averages >= 1):
                _fail(f"{where}.averages", averages, "the number of averages of the estimate (>= 1), "
                                                     "required with a coherence")
            object.__setattr__(self, "coherence", coherence)
            object.__setattr__(self, "averages", float(averages))

    @property
    def unit(self) -> str:
        """The response's unit (:func:`ratio_unit`)."""
        return ratio_unit(self.output, self.input)

    def hold_response(self) -> np.ndarray:
        """The response of the input's hold from its samples to the hub, which an estimate from the
        sampled input holds: ``sinc^2(f h)`` (linear, zero phase), ``sinc(f h) exp(-i pi f h)``
        (zero-order: half a sample of delay), 1 without a hold (``sinc x = sin(pi x) / (pi x)``)."""
        if self.hold is None:
            return np.ones(self.frequency.size, dtype=complex)
        x = self.frequency * self.sample_time
        if self.hold == "linear":
            return np.sinc(x) ** 2 + 0j
        return np.sinc(x) * np.exp(-1j * math.pi * x)

    def standard_error(self) -> np.ndarray:
        """Per frequency, the standard error of ``ln |H|`` and of the phase (rad) from the coherence
        (module docstring), at least :data:`MIN_RESPONSE_ERROR`; ones without a coherence (the fit
        then takes the scale from the residuals); ``inf`` where the coherence is 0."""
        if self.coherence is None:
            return np.ones(self.frequency.size)
        gamma2 = self.coherence
        with np.errstate(divide="ignore"):
            error = np.sqrt(1.0 - gamma2) / (np.sqrt(gamma2) * math.sqrt(2.0 * self.averages))
        return np.maximum(error, MIN_RESPONSE_ERROR)


@dataclass(frozen=True)
class PdLoop:
    """The loop a time series was taken in: ``u = kp (theta_r - theta) + kd (theta_r' - theta')`` on
    the hub angle (``kd = 0``: proportional), ``u`` the experiment's input (V with a drive, N m
    without); run as the ``pd`` maneuver of hubbeam (continuous, on the exact hub angle)."""

    kp: float
    kd: float = 0.0

    def __post_init__(self) -> None:
        for key in ("kp", "kd"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and value >= 0.0):
                _fail(f"loop.{key}", value, "a finite gain >= 0")
            object.__setattr__(self, key, float(value))
        if self.kp == 0.0:
            _fail("loop.kp", self.kp, "a gain > 0 (a loop on the hub angle)")


def sensor_spec(signal: str, entry: SensorSpec | Mapping | None, where: str) -> SensorSpec:
    """The sensor of ``signal``: a :class:`~hubbeam.model.maneuvers.SensorSpec` as it is, or from a
    mapping of its keys (``gain``, ``offset``, ``noise``, ``lowpass``, ``quantum``, ``mode``),
    checked as a sampled loop's sensor; an ideal sensor when None."""
    if isinstance(entry, SensorSpec):
        spec = entry
    else:
        entry = dict(entry or {})
        allowed = ("gain", "offset", "noise", "lowpass", "quantum", "mode")
        unknown = sorted(set(entry) - set(allowed))
        if unknown:
            _fail(f"{where}.{unknown[0]}", entry[unknown[0]], f"the keys {', '.join(allowed)}")
        spec = SensorSpec(signal=signal, **entry)
    if spec.signal != signal:
        _fail(f"{where}.signal", spec.signal, f"{signal!r}, the signal it reads")
    for key in ("gain", "offset", "noise", "lowpass", "quantum"):
        value = getattr(spec, key)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or (
                key not in ("gain", "offset") and value < 0.0) or (key == "gain" and value == 0.0):
            _fail(f"{where}.{key}", value, "a finite, non-zero number" if key == "gain" else
                  "a finite number" if key == "offset" else "a finite number >= 0 (0: none)")
    if spec.mode not in QUANTISATION_MODES:
        _fail(f"{where}.mode", spec.mode, f"one of {', '.join(QUANTISATION_MODES)}")
    return spec


@dataclass(frozen=True, eq=False)
class TimeSeries:
    """Samples at equally spaced ``time`` (s) of the ``input`` (``command``, None for a loop whose
    file holds no command, which reached the hub through the ``hold``) and the measured ``signals``
    (sensor units) read by their ``sensors``; open loop, or inside ``loop`` following ``reference``
    (rad)."""

    kind: ClassVar[str] = "time_series"
    name: str
    input: str
    time: np.ndarray
    command: np.ndarray | None
    signals: Mapping[str, np.ndarray]
    sensors: Mapping[str, SensorSpec] = field(default_factory=dict)
    excitation: str = "pulse"
    loop: PdLoop | None = None
    reference: np.ndarray | None = None
    hold: str = "linear"
    source: str = ""

    def __post_init__(self) -> None:
        where = f"experiment {_check_name(self.name)}"
        if self.input not in INPUTS:
            _fail(f"{where}.input", self.input, f"one of {', '.join(INPUTS)}")
        if self.hold not in HOLDS:
            _fail(f"{where}.hold", self.hold, f"one of {', '.join(HOLDS)}")
        if self.excitation not in EXCITATIONS:
            _fail(f"{where}.excitation", self.excitation, f"one of {', '.join(EXCITATIONS)}")
        time = _vector(f"{where}.time", self.time)
        steps = np.diff(time)
        if time.size < MIN_ROWS[self.kind] or steps.min() <= 0.0 or np.ptp(steps) > 1e-3 * steps.mean():
            _fail(f"{where}.time", f"<{time.size} values>",
                  f"at least {MIN_ROWS[self.kind]} equally spaced, increasing sample times")
        object.__setattr__(self, "time", time)
        if self.command is not None:
            object.__setattr__(self, "command", _vector(f"{where}.{self.input}", self.command, time.size))
        if not self.signals:
            _fail(f"{where}.signals", {}, f"at least one of {', '.join(SIGNALS)}")
        signals = {}
        for name, values in self.signals.items():
            if name not in SIGNALS:
                _fail(f"{where}.signals", name, f"the signals {', '.join(SIGNALS)}")
            signals[name] = _vector(f"{where}.{name}", values, time.size)
        unknown = sorted(set(self.sensors) - set(signals))
        if unknown:
            _fail(f"{where}.sensors.{unknown[0]}", "given", f"sensors of the measured signals {', '.join(signals)}")
        sensors = {name: sensor_spec(name, self.sensors.get(name), f"{where}.sensors.{name}") for name in signals}
        object.__setattr__(self, "signals", FrozenMap(signals))
        object.__setattr__(self, "sensors", FrozenMap(sensors))
        if self.loop is None:
            if self.command is None:
                _fail(f"{where}.{self.input}", None, "the input's samples (open loop)")
            if self.reference is not None:
                _fail(f"{where}.reference", "given", "a reference only with a loop")
        else:
            if not isinstance(self.loop, PdLoop):
                _fail(f"{where}.loop", self.loop, "a PdLoop (kp, kd)")
            if self.reference is None:
                _fail(f"{where}.reference", None, "the loop's hub-angle reference, one per sample")
            object.__setattr__(self, "reference", _vector(f"{where}.reference", self.reference, time.size))

    @property
    def step(self) -> float:
        """The sample time, s."""
        return float((self.time[-1] - self.time[0]) / (self.time.size - 1))

    def noise(self, signal: str) -> float:
        """The standard deviation of ``signal``'s reading about the sensor's model: its white noise
        and its quantisation counted as uniform noise, ``sqrt(noise^2 + quantum^2 / 12)``."""
        sensor = self.sensors[signal]
        return math.hypot(sensor.noise, sensor.quantum / math.sqrt(12.0))


#: an experiment of any kind
Experiment = ModalTest | FrequencyResponse | TimeSeries


def read_modal_test(path: os.PathLike | str, name: str | None = None, hub: str = "held",
                    speed: float = 0.0) -> ModalTest:
    """The :class:`ModalTest` of the file ``path`` (module docstring; ``name`` defaults to the
    file's stem)."""
    columns = [ColumnSpec("mode", ("1",)), ColumnSpec("frequency", ("Hz",)),
               ColumnSpec("damping_ratio", ("1",), False), ColumnSpec("log_decrement", ("1",), False),
               ColumnSpec("frequency_std", ("Hz",), False), ColumnSpec("damping_ratio_std", ("1",), False)]
    table = read_columns(path, columns, MIN_ROWS["modal"], "a modal test")
    values = table.values
    check_increasing(table, "mode")
    check_range(table, "mode", 1.0, math.inf, "mode numbers 1, 2, ... (1: the lowest bending mode)")
    whole = np.flatnonzero(values["mode"] != np.round(values["mode"]))
    if whole.size:
        raise ExperimentError(f"{table.where('mode', int(whole[0]))}: {float(values['mode'][whole[0]])!r}; allowed: "
                              "a whole mode number")
    check_range(table, "frequency", 0.0, math.inf, "a frequency > 0 Hz", include_low=False)
    check_increasing(table, "frequency")
    if "damping_ratio" in values and "log_decrement" in values:
        raise ExperimentError(f"{table.where('log_decrement', None)}: given with damping_ratio; allowed: one of "
                              "damping_ratio [1], log_decrement [1]")
    zeta = values.get("damping_ratio")
    if zeta is not None:
        check_range(table, "damping_ratio", 0.0, 1.0, "a damping ratio in [0, 1)", include_high=False)
    if "log_decrement" in values:
        check_range(table, "log_decrement", 0.0, math.inf, "a logarithmic decrement >= 0")
        delta = values["log_decrement"]
        zeta = delta / np.sqrt(4.0 * math.pi**2 + delta**2)
    for column in ("frequency_std", "damping_ratio_std"):
        if column in values:
            check_range(table, column, 0.0, math.inf, "a standard uncertainty > 0", include_low=False)
    if "damping_ratio_std" in values and zeta is None:
        raise ExperimentError(f"{table.where('damping_ratio_std', None)}: without damping ratios; allowed: "
                              "damping_ratio_std with damping_ratio or log_decrement")
    return ModalTest(name=name or Path(path).stem, hub=hub, mode=values["mode"].astype(int),
                     frequency=values["frequency"], frequency_std=values.get("frequency_std"),
                     damping_ratio=zeta, damping_ratio_std=values.get("damping_ratio_std"), speed=speed,
                     source=str(path))


def read_frequency_response(path: os.PathLike | str, input: str, output: str, name: str | None = None,
                            averages: float | None = None, hold: str | None = None,
                            sample_time: float | None = None) -> FrequencyResponse:
    """The :class:`FrequencyResponse` from ``input`` to ``output`` of the file ``path`` (module
    docstring); ``averages``: the number of averages of the estimate, required with a coherence;
    ``hold`` and ``sample_time``: the hold of a sampled input the estimate holds (None: none)."""
    if input not in INPUTS:
        _fail("input", input, f"one of {', '.join(INPUTS)}")
    if output not in SIGNALS:
        _fail("output", output, f"one of {', '.join(SIGNALS)}")
    unit = ratio_unit(output, input)
    columns = [ColumnSpec("frequency", ("Hz",)), ColumnSpec("magnitude", (unit, "dB"), False),
               ColumnSpec("phase", ("deg", "rad"), False), ColumnSpec("real", (unit,), False),
               ColumnSpec("imag", (unit,), False), ColumnSpec("coherence", ("1",), False)]
    table = read_columns(path, columns, MIN_ROWS["frequency_response"], f"a frequency response to {output}")
    values, units = table.values, table.units
    polar, cartesian = {"magnitude", "phase"} & set(values), {"real", "imag"} & set(values)
    if (len(polar) == 2) == (len(cartesian) == 2) or len(polar) == 1 or len(cartesian) == 1:
        raise ExperimentError(f"{table.where(None)}, line {table.header_line}: columns "
                              f"{', '.join(sorted(polar | cartesian)) or 'none'} of the response; allowed: "
                              f"magnitude [{unit}] and phase [deg], or real [{unit}] and imag [{unit}]")
    check_range(table, "frequency", 0.0, math.inf, "a frequency > 0 Hz", include_low=False)
    check_increasing(table, "frequency")
    if polar:
        magnitude = values["magnitude"]
        if units["magnitude"] == "dB":
            magnitude = 10.0 ** (magnitude / 20.0)
        else:
            check_range(table, "magnitude", 0.0, math.inf, "a magnitude > 0", include_low=False)
        phase = values["phase"] if units["phase"] == "rad" else np.radians(values["phase"])
        response = magnitude * np.exp(1j * phase)
    else:
        response = values["real"] + 1j * values["imag"]
        zero = np.flatnonzero(response == 0.0)
        if zero.size:
            raise ExperimentError(f"{table.where('real', int(zero[0]))}: a zero response; allowed: a non-zero "
                                  "response (its logarithm is fitted)")
    if "coherence" in values:
        check_range(table, "coherence", 0.0, 1.0, "a coherence in [0, 1]")
    return FrequencyResponse(name=name or Path(path).stem, input=input, output=output, frequency=values["frequency"],
                             response=response, coherence=values.get("coherence"), averages=averages,
                             hold=hold, sample_time=sample_time, source=str(path))


def read_time_series(path: os.PathLike | str, input: str, name: str | None = None,
                     sensors: Mapping | None = None, loop: PdLoop | Mapping | None = None,
                     excitation: str = "pulse", hold: str = "linear") -> TimeSeries:
    """The :class:`TimeSeries` of the file ``path`` (module docstring): ``input`` the hub's input
    (reaching it through ``hold``), ``sensors`` the sensors of the measured signals by name
    (mappings or ``SensorSpec``), ``loop`` the PD loop the data were taken in (a :class:`PdLoop` or
    ``{kp, kd}``; None: open loop)."""
    if input not in INPUTS:
        _fail("input", input, f"one of {', '.join(INPUTS)}")
    if isinstance(loop, Mapping):
        loop = PdLoop(**loop)
    columns = [ColumnSpec("time", ("s",)), ColumnSpec(input, (INPUT_UNITS[input],), loop is None),
               ColumnSpec("reference", ("rad",), loop is not None),
               *(ColumnSpec(signal, (OUTPUTS[signal][0],), False) for signal in SIGNALS)]
    if loop is None:
        columns = [spec for spec in columns if spec.name != "reference"]
    table = read_columns(path, columns, MIN_ROWS["time_series"], f"a time series driven by {input}")
    check_increasing(table, "time")
    uniform_step(table, "time")
    signals = {signal: table.values[signal] for signal in SIGNALS if signal in table.values}
    if not signals:
        raise ExperimentError(f"{table.where(None)}, line {table.header_line}: no measured signal; allowed: at "
                              f"least one of {', '.join(f'{s} [{OUTPUTS[s][0]}]' for s in SIGNALS)}")
    return TimeSeries(name=name or Path(path).stem, input=input, time=table.values["time"],
                      command=table.values.get(input), signals=signals, sensors=dict(sensors or {}),
                      excitation=excitation, loop=loop, reference=table.values.get("reference"), hold=hold,
                      source=str(path))


def write_experiment(experiment: Experiment, path: os.PathLike | str, comments: tuple[str, ...] = ()) -> Path:
    """Write ``experiment`` as the file its reader reads (a frequency response as magnitude and
    phase in degrees; its settings that are not columns, such as the hub or the sensors, belong to
    the experiment's entry, not to the file)."""
    if isinstance(experiment, ModalTest):
        columns = {"mode": ("1", experiment.mode), "frequency": ("Hz", experiment.frequency),
                   "frequency_std": ("Hz", experiment.frequency_std)}
        if experiment.damping_ratio is not None:
            columns |= {"damping_ratio": ("1", experiment.damping_ratio),
                        "damping_ratio_std": ("1", experiment.damping_ratio_std)}
    elif isinstance(experiment, FrequencyResponse):
        columns = {"frequency": ("Hz", experiment.frequency),
                   "magnitude": (experiment.unit, np.abs(experiment.response)),
                   "phase": ("deg", np.degrees(np.angle(experiment.response)))}
        if experiment.coherence is not None:
            columns["coherence"] = ("1", experiment.coherence)
    else:
        columns = {"time": ("s", experiment.time)}
        if experiment.command is not None:
            columns[experiment.input] = (INPUT_UNITS[experiment.input], experiment.command)
        if experiment.reference is not None:
            columns["reference"] = ("rad", experiment.reference)
        columns |= {name: (OUTPUTS[name][0], values) for name, values in experiment.signals.items()}
    return write_columns(path, columns, comments)


__all__ = ["DAMPING_UNCERTAINTY", "EXCITATIONS", "FREQUENCY_UNCERTAINTY", "HOLDS", "HUBS", "INPUTS", "SIGNALS",
           "Experiment", "FrequencyResponse", "ModalTest", "PdLoop", "TimeSeries", "ratio_unit",
           "read_frequency_response", "read_modal_test", "read_time_series", "sensor_spec", "write_experiment"]
