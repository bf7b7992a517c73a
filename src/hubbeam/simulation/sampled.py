"""A sampled digital controller on the hub, as the compiled loop runs it (``docs/sampled-control.md``).

A :class:`SampledLoop` (its sensors, :class:`~hubbeam.model.maneuvers.SensorSpec`, and their rows on the
simulated model's state, the controller's matrices, the sample time ``Ts``,
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
from hubbeam.model.maneuvers import QUANTISATION_MODES, SensorSpec, Tracking
from hubbeam.simulation.errors import SimulationError

LOG = logging.getLogger(__name__)

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


#: the controller's matrices and their shapes in the sizes ``nc`` (controller states), ``ns``
#: (estimated states) and ``p`` (sensors): the convention of ``docs/sampled-control.md``
MATRIX_SHAPES = {"Ac": ("nc", "nc"), "Bc": ("nc", "p"), "Bu": ("nc",), "E": ("ns", "nc"), "F": ("ns", "p"),
                 "K": ("ns",), "R_m": ("p", 3), "U_r": (3,), "xc0": ("nc",)}


@dataclass(frozen=True, eq=False)
class SampledLoop:
    """A sampled digital controller on the hub (``docs/sampled-control.md``): at ``t_k = k Ts`` the
    ``sensors`` (:class:`~hubbeam.model.maneuvers.SensorSpec`, each named by its signal) read ``s_j
    = gain_j (rows_j . x) + offset_j`` on the state ``x = (y, y')`` of the simulated model
    (``rows``: p x 2 N, ``N = 1 + 2 n``, one more with a root spring: coordinates ``theta, q1, q2``,
    the root spring's hub angle last when there is one, then their rates; linear output rows such as
    those of ``hubbeam.linear.statespace``), low-passed, noisy and quantised, and give ``m_k``,
    ``e_k = m_k - R_m rho_k`` (``rho_k``: the reference's angle, rate and acceleration), ``xhat_k =
    E xc_k + F e_k``, ``u_k = clip(U_r . rho_k - K . xhat_k, -u_max, u_max)``, ``xc_{k+1} = Ac xc_k
    + Bc e_k + Bu (u_k - U_r . rho_k)``, and ``u_k`` acts from ``t_k + D Ts`` to ``t_(k+1) + D Ts``
    (``u_init`` before the first command arrives). ``u`` is the hub's input: volts with a drive, N m
    without. ``seed`` draws the sensors' noise (``numpy.random.default_rng``). ``estimate_states``
    and ``estimate_units`` name the estimate's components and their units (default ``x_1``, ...,
    unit ``1``). Every value is checked when the loop is made."""

    sensors: tuple[SensorSpec, ...]
    rows: np.ndarray
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
        if not sensors or not all(isinstance(sensor, SensorSpec) for sensor in sensors):
            raise SimulationError(f"SampledLoop.sensors = {self.sensors!r}; allowed: a non-empty list "
                                  "of SensorSpec")
        for sensor in sensors:
            problem = sensor.problem()
            if problem is not None:
                key, value, allowed = problem
                raise SimulationError(f"sensor {sensor.signal!r}.{key} = {value!r}; allowed: {allowed}")
        names = [sensor.signal for sensor in sensors]
        if len(set(names)) < len(names):
            raise SimulationError(f"SampledLoop.sensors: signals {names}; allowed: distinct signals")
        rows = _array(self.rows)
        if rows.ndim != 2 or rows.shape[0] != len(sensors) or rows.shape[1] < 2 or rows.shape[1] % 2 or \
                not np.all(np.isfinite(rows)):
            raise SimulationError(f"SampledLoop.rows: shape {np.shape(self.rows)}; allowed: finite values of shape "
                                  f"(p, 2 N), a row per sensor (p = {len(sensors)}) on the state (y, y')")
        object.__setattr__(self, "rows", np.ascontiguousarray(rows))
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
                "sensors": json.dumps([sensor_record(sensor, row) for sensor, row in zip(self.sensors, self.rows)]),
                "controller": json.dumps({name: getattr(self, name).tolist() for name in MATRIX_SHAPES})}


def sensor_unit(sensor: SensorSpec) -> str:
    """A loop's sensor's unit: its own, ``1`` when not said."""
    return sensor.unit or "1"


def sensor_record(sensor: SensorSpec, row: np.ndarray) -> dict:
    """A loop's sensor with its row as plain values (a dataset's attributes)."""
    return {"name": sensor.signal, "row": row.tolist(), "gain": sensor.gain, "offset": sensor.offset,
            "noise": sensor.noise, "lowpass": sensor.lowpass, "quantum": sensor.quantum, "mode": sensor.mode,
            "unit": sensor_unit(sensor)}


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
    N = loop.rows.shape[1] // 2
    columns = np.concatenate([free, N + free])
    samples = loop.sample_times(t_end)
    n, p, ns = samples.size, loop.sizes["p"], loop.sizes["ns"]
    noise = loop.noise(n)
    sensors = LoopSensors(
        np.ascontiguousarray(loop.rows[:, columns]),
        *(np.array([float(getattr(sensor, key)) for sensor in loop.sensors])
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
