"""The rig between a controller and the beam: a DC drive on the hub and a sampled digital
controller with its sensors, run by the compiled kernels (``docs/sampled-control.md``).

* A drive (:class:`hubbeam.model.drive.DcMotor`) turns a free hub's maneuver output into the hub
  torque (volts in), its rotor's reflected inertia joins the hub inertia
  (:func:`drive_matrices`), and a prescribed hub reports the voltage it would need; the output
  array gains ``hub_voltage`` and ``motor_torque`` (``hubbeam.core.integrate.SCALAR_OUTPUTS``).
* A :class:`SampledLoop` (its :class:`Sensor` rows, the controller's matrices, the sample time
  ``Ts``, the delay ``D``, the saturation ``u_max``, the input ``u_init`` before the first command
  and the seed of the sensor noise) replaces the law of a tracking maneuver (``pd`` or
  ``state_feedback``) and keeps its reference motion; :mod:`hubbeam.core.sampled` runs it.

:func:`simulate_rig` runs a case with either or both and returns the arrays a dataset holds: the
usual output array and, with a loop, the records of every sample (:class:`RigRun`).
"""

from __future__ import annotations

import json
import logging
import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from hubbeam.configuration.settings import Case, Numerics, simulation_settings
from hubbeam.core import maneuver as kernel_maneuvers
from hubbeam.core import radau
from hubbeam.core.eom import free_coordinates
from hubbeam.core.inputs import (
    IDENTITY_SHAPER,
    NO_DRIVE,
    LoopArrays,
    LoopMatrices,
    LoopSensors,
    LoopTiming,
    SampleRecords,
    SimulationInputs,
)
from hubbeam.core.integrate import n_output_columns
from hubbeam.core.sampled import EDGES, ROUND, simulate_sampled_kernel
from hubbeam.model.damping import damping_matrices
from hubbeam.model.drive import DcMotor
from hubbeam.model.maneuvers import MANEUVERS, Tracking
from hubbeam.model.matrices import SystemMatrices
from hubbeam.model.models import model
from hubbeam.model.parameters import BeamParameters
from hubbeam.model.root import RootSpring, checked_spring, joint_inputs
from hubbeam.simulation.simulate import (
    INTEGRATOR,
    SimulationError,
    _integrate,
    case_matrices,
    initial_state,
    integrator_settings,
    output_times,
)

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
    edges: the step below)."""

    name: str
    row: np.ndarray
    gain: float = 1.0
    offset: float = 0.0
    noise: float = 0.0
    lowpass: float = 0.0
    quantum: float = 0.0
    mode: str = "round"

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
                "noise": self.noise, "lowpass": self.lowpass, "quantum": self.quantum, "mode": self.mode}


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
    (``numpy.random.default_rng``). Every value is checked when the loop is made."""

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


class RigRun(NamedTuple):
    """A run of :func:`simulate_rig`: the output grid ``t``, the output array ``out`` (columns
    ``hubbeam.core.integrate.output_columns``), radau5's ``status`` and ``t_stop``, the integrator's
    attributes (as ``hubbeam.simulation.simulate.build_dataset`` takes them), the system
    ``matrices`` run (the rotor's reflected inertia in ``Jh``), and with a loop its
    :class:`~hubbeam.core.inputs.SampleRecords` ``records`` (NaN after the stop) and the sensor
    noise ``noise`` it drew (else None)."""

    t: np.ndarray
    out: np.ndarray
    status: int
    t_stop: float
    integrator: dict
    matrices: SystemMatrices
    records: SampleRecords | None = None
    noise: np.ndarray | None = None


def drive_matrices(sm: SystemMatrices, motor: DcMotor | None) -> SystemMatrices:
    """``sm`` with the rotor's reflected inertia (``DcMotor.reflected_inertia``) added to the hub's
    ``Jh`` (``sm`` itself without a motor)."""
    return sm if motor is None else sm._replace(Jh=float(sm.Jh) + motor.reflected_inertia)


def packed_drive(motor: DcMotor | None) -> np.ndarray:
    """The kernels' drive array of ``motor`` (``hubbeam.core.drive``; none: an ideal actuator)."""
    if motor is None:
        return NO_DRIVE
    if not isinstance(motor, DcMotor):
        raise SimulationError(f"motor = {motor!r}; allowed: a hubbeam.model.drive.DcMotor or None")
    return motor.packed()


def reference_array(maneuver: Tracking) -> np.ndarray:
    """The reference of a tracking maneuver packed as the kernels read it, ``[kind, parameters...]``
    (``hubbeam.core.maneuver.reference_motion`` at offset 1)."""
    return np.ascontiguousarray(maneuver.reference_parameters())


def loop_arrays(loop: SampledLoop, free: np.ndarray, t_end: float,
                reference: np.ndarray) -> tuple[LoopArrays, np.ndarray, np.ndarray]:
    """The kernel's :class:`~hubbeam.core.inputs.LoopArrays` of ``loop`` for the integrated
    coordinates ``free`` (``hubbeam.core.eom.free_coordinates``), the last output time ``t_end`` and the
    packed ``reference`` (:func:`reference_array`), with NaN records; the stops of the
    integration (every sample and switch time in ``(0, t_end]``); the noise drawn."""
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
    return LoopArrays(matrices, sensors, timing, reference, records), stops, noise


def held_table(samples: int, u_init: float) -> np.ndarray:
    """The ``HELD`` maneuver's table (``hubbeam.core.maneuver``) with room for a switch per sample
    after the first entry: ``u_init`` from ``t = 0``."""
    capacity = samples + 1
    mp = np.zeros(1 + 2 * capacity)
    mp[0] = 1.0
    mp[1 + capacity] = u_init
    return mp


def _loop_case(case: Case) -> None:
    """``SimulationError`` unless ``case``'s maneuver tracks a reference the loop can take."""
    if not isinstance(case.maneuver, Tracking):
        tracking = [kind for kind, record in MANEUVERS.items() if issubclass(record, Tracking)]
        raise SimulationError(f"cases.{case.label}.maneuver.kind = {case.maneuver.kind!r} with a sampled loop; "
                              f"allowed: one of {', '.join(tracking)} (the loop replaces its law and tracks its "
                              "reference)")


def simulate_rig(case: Case | Mapping, params: BeamParameters, numerics: Numerics | Mapping, *,
                 motor: DcMotor | None = None, loop: SampledLoop | None = None, matrices: SystemMatrices | None = None,
                 feedback=None, root_spring: RootSpring | None = None) -> RigRun:
    """Run ``case`` with the hub's drive ``motor`` and/or the sampled controller ``loop``.

    ``case``, ``params``, ``numerics``, ``matrices`` and ``feedback`` as in
    :func:`hubbeam.simulation.simulate.simulate` (checked the same way). Without a loop the case's
    maneuver runs as in a simulation, its output (torque, or with a motor volts) going through the
    drive. With a loop the case's maneuver must track a reference (``pd``, ``state_feedback``): the
    loop replaces its law (the maneuver's gains are not used) and samples its reference; the
    sensors' rows must have the length ``2 N`` of the case's model. The rotor's reflected inertia
    joins the hub inertia (:func:`drive_matrices`). With a compliant root ``root_spring`` (as in
    ``simulate``) the drive and the loop act on the hub angle ``phi``, the state is that of
    ``(theta, q1, q2, phi)`` (sensor rows of length ``2 (N + 1)``) and the rotor stays on the hub's
    side of the spring.
    """
    root_spring = checked_spring(root_spring)
    case, numerics = simulation_settings(case, numerics, params.L)
    if loop is not None:
        if not isinstance(loop, SampledLoop):
            raise SimulationError(f"loop = {loop!r}; allowed: a SampledLoop or None")
        _loop_case(case)
    drive = packed_drive(motor)
    sm = drive_matrices(case_matrices(case, params, numerics, matrices), motor)
    if loop is None:
        return RigRun(*_integrate(case, params, numerics, sm, feedback, drive, root_spring=root_spring), sm)
    n = case.modes
    joint = root_spring is not None
    N = 2 + 2 * n if joint else 1 + 2 * n
    if loop.sensors[0].row.size != 2 * N:
        raise SimulationError(f"SampledLoop.sensors: rows of length {loop.sensors[0].row.size}; allowed: "
                              f"2 N = {2 * N}, the state (y, y') of {case.model} with {n} modes"
                              + (" and the root spring's hub angle" if joint else ""))
    traits = model(case.model).traits
    t = output_times(case.t_end, numerics.output_step)
    link, root = joint_inputs(sm, root_spring)
    inputs = SimulationInputs(traits, kernel_maneuvers.HELD, held_table(0, loop.u_init),
                              damping_matrices(case.damping, sm), link, drive, IDENTITY_SHAPER, root)
    arrays, stops, noise = loop_arrays(loop, free_coordinates(inputs), t[-1], reference_array(case.maneuver))
    inputs = inputs._replace(mp=held_table(arrays.timing.sample_times.size, loop.u_init))
    out = np.empty((t.size, n_output_columns(n, joint)))
    stats = np.zeros(len(radau.STAT_NAMES), dtype=np.int64)
    start = time.perf_counter()
    status, t_stop = simulate_sampled_kernel(inputs, initial_state(case, sm, joint), t, stops,
                                             integrator_settings(numerics, params.L), arrays, out, stats)
    LOG.info("case %s (%s, %d modes) under a sampled loop at %g s: %s at t = %g s, %.3f s wall, %d steps "
             "(%d rejected)", case.label, case.model, n, loop.Ts,
             radau.STATUS_NAMES[status], t_stop, time.perf_counter() - start, stats[radau.ACCEPTED],
             stats[radau.REJECTED])
    integrator = {"integrator": INTEGRATOR, "rtol": float(numerics.rtol), "atol": float(numerics.atol),
                  **{name: int(value) for name, value in zip(radau.STAT_NAMES, stats)}}
    return RigRun(t, out, status, t_stop, integrator, sm, arrays.records, noise)
