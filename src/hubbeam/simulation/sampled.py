"""A sampled digital controller on the hub, as the compiled loop runs it (``docs/sampled-control.md``).

A :class:`SampledLoop` (its :class:`Sensor` rows, the controller's matrices, the sample time ``Ts``,
the delay ``D``, the saturation ``u_max``, the input ``u_init`` before the first command and the
seed of the sensor noise) replaces the law of a tracking maneuver (``pd`` or ``state_feedback``) and
keeps its reference motion; :mod:`hubbeam.core.sampled` runs it and
:func:`hubbeam.simulation.simulate.simulate` builds its dataset. Here: the loop and its checks, and
its packing into the kernel's arrays (:func:`loop_arrays`, :func:`held_table`).
"""

from __future__ import annotations

import json
import logging
import math
from dataclasses import dataclass, field

import numpy as np

from hubbeam.core.inputs import (
    LoopArrays,
    LoopMatrices,
    LoopSensors,
    LoopTiming,
    SampleRecords,
)
from hubbeam.core.sampled import EDGES, ROUND
from hubbeam.model.maneuvers import Tracking
from hubbeam.simulation.errors import SimulationError

LOG = logging.getLogger(__name__)

#: quantisation modes of a sensor: the kernel's codes (``hubbeam.core.sampled``)
QUANTISATION_MODES = {"round": ROUND, "edges": EDGES}
#: a fractional delay must keep its switches this fraction of a sample time away from the samples
#: (closer, the integrator would take slivers of steps between them)
MIN_DELAY_FRACTION = 1e-6


def _number(where: str, value, test, allowed: str) -> float:
    """``value`` as a float if ``test`` accepts it; ``SimulationError`` naming ``where`` otherwise."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, bool) or not test(number):
        raise SimulationError(f"{where} = {value!r}; allowed: {allowed}")
    return number


def _array(value) -> np.ndarray:
    """``value`` as a float array (NaN, which no check accepts, where it holds no numbers)."""
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return np.full(np.shape(value) or 1, np.nan)


def _finite(x: float) -> bool:
    return math.isfinite(x)


def _not_negative(x: float) -> bool:
    return 0.0 <= x < math.inf


@dataclass(frozen=True, eq=False)
class Sensor:
    """A sensor of a sampled loop: ``s = gain (row . x) + offset`` on the state ``x = (y, y')`` of
    the simulated model (``row``: length ``2 N``, ``N = 1 + 2 n``, coordinates ``theta, q1, q2``
    then their rates; a linear output row such as those of ``hubbeam.linear.statespace``), the
    analog first-order low-pass of time constant ``lowpass`` (s; 0: none), white noise of standard
    deviation ``noise`` (in the sensor's unit) and the quantisation step ``quantum`` (0: none),
    ``mode`` ``"round"`` (to the nearest step) or ``"edges"`` (an incremental encoder counting
    edges: the step below). ``unit`` names the sensor's unit (UDUNITS; ``1`` when not said)."""

    name: str
    row: np.ndarray
    gain: float = 1.0
    offset: float = 0.0
    noise: float = 0.0
    lowpass: float = 0.0
    quantum: float = 0.0
    mode: str = "round"
    unit: str = "1"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise SimulationError(f"Sensor.name = {self.name!r}; allowed: a non-empty string")
        where = f"Sensor {self.name!r}"
        row = _array(self.row)
        if row.ndim != 1 or row.size < 2 or row.size % 2 or not np.all(np.isfinite(row)):
            raise SimulationError(f"{where}.row = {np.asarray(self.row).tolist()!r}; allowed: finite values on "
                                  "the state (y, y'), 2 N of them")
        object.__setattr__(self, "row", row)
        object.__setattr__(self, "gain", _number(f"{where}.gain", self.gain, _finite, "a finite number"))
        object.__setattr__(self, "offset", _number(f"{where}.offset", self.offset, _finite,
                                                   "a finite number"))
        for key in ("noise", "lowpass", "quantum"):
            object.__setattr__(self, key, _number(f"{where}.{key}", getattr(self, key), _not_negative,
                                                  "a finite number >= 0 (0: none)"))
        if self.mode not in QUANTISATION_MODES:
            raise SimulationError(f"{where}.mode = {self.mode!r}; allowed: one of "
                                  f"{', '.join(QUANTISATION_MODES)}")

    def to_dict(self) -> dict:
        """The sensor as plain values (for a dataset's attributes)."""
        return {"name": self.name, "row": self.row.tolist(), "gain": self.gain, "offset": self.offset,
                "noise": self.noise, "lowpass": self.lowpass, "quantum": self.quantum, "mode": self.mode,
                "unit": self.unit}


#: the controller's matrices and their shapes in the sizes ``nc`` (controller states), ``ns``
#: (estimated states) and ``p`` (sensors): the convention of ``docs/sampled-control.md``
MATRIX_SHAPES = {"Ac": ("nc", "nc"), "Bc": ("nc", "p"), "Bu": ("nc",), "E": ("ns", "nc"), "F": ("ns", "p"),
                 "K": ("ns",), "R_m": ("p", 3), "U_r": (3,), "xc0": ("nc",)}


@dataclass(frozen=True, eq=False)
class SampledLoop:
    """A sampled digital controller on the hub (``docs/sampled-control.md``): at ``t_k = k Ts``
    the sensors give ``m_k``, ``e_k = m_k - R_m rho_k`` (``rho_k``: the reference's angle, rate and
    acceleration), ``xhat_k = E xc_k + F e_k``, ``u_k = clip(U_r . rho_k - K . xhat_k, -u_max,
    u_max)``, ``xc_{k+1} = Ac xc_k + Bc e_k + Bu (u_k - U_r . rho_k)``, and ``u_k`` acts from ``t_k
    + D Ts`` to ``t_(k+1) + D Ts`` (``u_init`` before the first command arrives). ``u`` is the
    hub's input: volts with a drive, N m without. ``seed`` draws the sensors' noise
    (``numpy.random.default_rng``). ``estimate_states`` and ``estimate_units`` name the estimate's
    components and their units (default ``x_1``, ..., unit ``1``). Every value is checked when the
    loop is made."""

    sensors: tuple[Sensor, ...]
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
    D: float = 0.0
    u_max: float = math.inf
    u_init: float = 0.0
    seed: int = 0
    estimate_states: tuple[str, ...] = ()
    estimate_units: tuple[str, ...] = ()
    sizes: dict = field(init=False, repr=False)

    def __post_init__(self) -> None:
        sensors = tuple(self.sensors) if isinstance(self.sensors, (list, tuple)) else ()
        if not sensors or not all(isinstance(sensor, Sensor) for sensor in sensors):
            raise SimulationError(f"SampledLoop.sensors = {self.sensors!r}; allowed: a non-empty list "
                                  "of Sensor")
        names = [sensor.name for sensor in sensors]
        if len(set(names)) < len(names):
            raise SimulationError(f"SampledLoop.sensors: names {names}; allowed: distinct names")
        lengths = {sensor.row.size for sensor in sensors}
        if len(lengths) > 1:
            raise SimulationError(f"SampledLoop.sensors: rows of lengths {sorted(lengths)}; allowed: "
                                  "rows of one length, 2 N of the simulated model")
        object.__setattr__(self, "sensors", sensors)
        matrices = {name: _array(getattr(self, name)) for name in MATRIX_SHAPES}
        if matrices["Ac"].ndim != 2 or matrices["K"].ndim != 1:
            name = "Ac" if matrices["Ac"].ndim != 2 else "K"
            raise SimulationError(f"SampledLoop.{name}: shape {matrices[name].shape}; allowed: "
                                  f"{'a square matrix (nc, nc)' if name == 'Ac' else 'a vector of ns gains'}")
        sizes = {"p": len(sensors), "nc": matrices["Ac"].shape[0], "ns": matrices["K"].size}
        for name, shape in MATRIX_SHAPES.items():
            value = matrices[name]
            expected = tuple(sizes.get(size, size) for size in shape)
            if value.shape != expected or not np.all(np.isfinite(value)):
                dims = ", ".join(str(size) for size in shape)
                raise SimulationError(
                    f"SampledLoop.{name}: shape {value.shape}; allowed: finite values of shape ({dims}) = "
                    f"{expected}, nc = Ac.shape[0] = {sizes['nc']} (Ac square), ns = K.size = {sizes['ns']}, "
                    f"p = len(sensors) = {sizes['p']}")
            object.__setattr__(self, name, np.ascontiguousarray(value))
        object.__setattr__(self, "sizes", sizes)
        object.__setattr__(self, "Ts", _number("SampledLoop.Ts", self.Ts, lambda x: 0.0 < x < math.inf,
                                               "a finite sample time > 0 s"))
        fraction = f"whole, or with a fractional part in [{MIN_DELAY_FRACTION:g}, 1 - {MIN_DELAY_FRACTION:g}]"
        D = _number("SampledLoop.D", self.D, _not_negative, f"a finite delay >= 0 samples, {fraction}")
        part = D - math.floor(D)
        if 0.0 < part < MIN_DELAY_FRACTION or part > 1.0 - MIN_DELAY_FRACTION:
            raise SimulationError(f"SampledLoop.D = {self.D!r}; allowed: a delay {fraction} (a switch "
                                  "so close to a sample would leave the integrator a sliver of a step)")
        object.__setattr__(self, "D", D)
        object.__setattr__(self, "u_max", _number("SampledLoop.u_max", self.u_max, lambda x: x > 0.0,
                                                  "a saturation > 0 (inf: none)"))
        object.__setattr__(self, "u_init", _number("SampledLoop.u_init", self.u_init, _finite,
                                                   "a finite input"))
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or self.seed < 0:
            raise SimulationError(f"SampledLoop.seed = {self.seed!r}; allowed: an integer >= 0")
        ns = sizes["ns"]
        names = tuple(self.estimate_states) or tuple(f"x_{i}" for i in range(1, ns + 1))
        units = tuple(self.estimate_units) or ("1",) * ns
        if len(names) != ns or len(units) != ns:
            raise SimulationError(f"SampledLoop.estimate_states / estimate_units: {len(names)} and {len(units)} "
                                  f"entries; allowed: one per estimated state, ns = {ns}")
        object.__setattr__(self, "estimate_states", names)
        object.__setattr__(self, "estimate_units", units)

    def sample_times(self, t_end: float) -> np.ndarray:
        """``t_k = k Ts`` for every ``k`` with ``t_k <= t_end``."""
        count = int(math.floor(t_end / self.Ts)) + 2
        times = np.arange(count) * self.Ts
        return times[times <= t_end]

    def switch_times(self, samples: int) -> np.ndarray:
        """``(k + D) Ts``, when the command of sample ``k`` reaches the plant (whole ``D``: sample
        times, bit for bit)."""
        return (np.arange(samples) + self.D) * self.Ts

    def noise(self, samples: int) -> np.ndarray:
        """The standard normal ``w`` (``samples`` x p) of the sensors' noise, drawn from ``seed``."""
        return np.random.default_rng(self.seed).standard_normal((samples, self.sizes["p"]))

    def attributes(self) -> dict:
        """The loop as a dataset's attributes: settings, sensors and matrices (JSON)."""
        return {"sample_time_s": self.Ts, "delay_samples": self.D, "input_limit": self.u_max,
                "initial_input": self.u_init, "noise_seed": int(self.seed),
                "sensors": json.dumps([sensor.to_dict() for sensor in self.sensors]),
                "controller": json.dumps({name: getattr(self, name).tolist() for name in MATRIX_SHAPES})}


def reference_array(maneuver: Tracking) -> np.ndarray:
    """The reference of a tracking maneuver packed as the kernels read it, ``[kind, parameters...]``
    (``hubbeam.core.maneuver.reference_motion`` at offset 1)."""
    return np.ascontiguousarray(maneuver.reference_parameters())


def loop_arrays(loop: SampledLoop, free: np.ndarray, t_end: float, reference: np.ndarray,
                shaper: np.ndarray) -> tuple[LoopArrays, np.ndarray, np.ndarray]:
    """The kernel's :class:`~hubbeam.core.inputs.LoopArrays` of ``loop`` for the integrated
    coordinates ``free`` (``hubbeam.core.eom.free_coordinates``), the last output time ``t_end``, the
    packed ``reference`` (:func:`reference_array`) and the ``shaper`` array of its command shaper,
    with NaN records; the stops of the integration (every sample and switch time in ``(0,
    t_end]``); the noise drawn."""
    N = loop.sensors[0].row.size // 2
    columns = np.concatenate([free, N + free])
    samples = loop.sample_times(t_end)
    n, p, ns = samples.size, loop.sizes["p"], loop.sizes["ns"]
    noise = loop.noise(n)
    sensors = LoopSensors(
        np.ascontiguousarray([sensor.row[columns] for sensor in loop.sensors]),
        *(np.array([getattr(sensor, key) for sensor in loop.sensors], dtype=float)
          for key in ("gain", "offset", "noise", "lowpass", "quantum")),
        np.array([QUANTISATION_MODES[sensor.mode] for sensor in loop.sensors], dtype=np.int64), noise)
    switches = loop.switch_times(n)
    timing = LoopTiming(samples, switches, loop.u_max)
    records = SampleRecords(np.full(n, np.nan), np.full((n, p), np.nan), np.full((n, p), np.nan),
                            np.full((n, ns), np.nan), np.full(n, np.nan), np.full(n, np.nan))
    stops = np.union1d(samples, switches)
    stops = np.ascontiguousarray(stops[(stops > 0.0) & (stops <= t_end)])
    matrices = LoopMatrices(*(getattr(loop, name) for name in MATRIX_SHAPES))
    return LoopArrays(matrices, sensors, timing, reference, records, shaper), stops, noise


def held_table(samples: int, u_init: float) -> np.ndarray:
    """The ``HELD`` maneuver's table (``hubbeam.core.maneuver``) with room for a switch per sample
    after the first entry: ``u_init`` from ``t = 0``."""
    capacity = samples + 1
    mp = np.zeros(1 + 2 * capacity)
    mp[0] = 1.0
    mp[1 + capacity] = u_init
    return mp
