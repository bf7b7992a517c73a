"""Synthetic rig data: the three kinds of experiment made from hubbeam's own CFOAM, seeded and recorded.

No measured data set of a flexible link on a servo with an open licence was found, so the
identification is tested, and its shipped example runs, on data made here. The rig
(:func:`rig_case`) is a small arm like the Quanser Rotary Flexible Link: a 0.6 m aluminium strip
(25 mm x 2 mm: ``rhoA = 0.135 kg/m``, ``EI = 1.15 N m2``) clamped through a compliant bracket
(a root spring of 30 N m/rad) to the SRV02 servo (``hubbeam.model.drive.QUANSER_SRV02``), a
15 g payload carrying the accelerometer 3 cm inward of the tip; CFOAM with three modes, modal
damping. That is the *nominal* case a user would configure. The data come from the *true* plant,
the nominal case with the parameters :data:`TRUTH` applied
(:func:`hubbeam.identification.parameters.apply`), through
:class:`~hubbeam.identification.plant.CasePlant`, read by the rig's sensors (:data:`SENSORS`: the
SRV02's 4096-count encoder counting edges, a strain gauge on the link's deflection angle through a
12-bit converter, an accelerometer), each reading ``quantise(gain x signal + offset + noise)`` as
the sampled loop's sensors (``hubbeam.core.sampled``):

* :func:`modal_test`: the bending modes of the true plant's linearisation (exact for small
  motions), hub held or free, with Gaussian relative errors on the frequencies and the damping
  ratios (a tap test's modal fit);
* :func:`free_oscillation`: the courseware's test, the hub held and the link released from a tip
  deflection, simulated, read by the strain gauge;
* :func:`measured`: any time series (a voltage pulse, a swept sine, a step inside a PD loop on the
  hub angle), simulated and read by the sensors; the input column is the commanded voltage (in a
  loop, the command the loop computed); and the frequency responses are H1 estimates of a swept
  sine's time series (:func:`hubbeam.identification.spectra.frequency_response_estimate`).

Every random number comes from ``numpy.random.default_rng`` seeded by one integer, each experiment
from its own child of a ``SeedSequence``. ``python -m hubbeam.identification.synthetic --output
<folder> --seed <n>`` writes the shipped data set (``studies/identification_rig``): the experiment
files and ``synthetic.json`` with the seed, the true values, the nominal case and the settings. The
study that identifies the rig from them (``study.yaml`` in that folder) is written by hand; a test
checks that its rig is the nominal one of this module.
"""

from __future__ import annotations

import argparse
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from hubbeam.configuration.settings import simulation_settings
from hubbeam.identification.experiments import FrequencyResponse, ModalTest, PdLoop, TimeSeries, write_experiment
from hubbeam.identification.files import write_columns
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import first_order_lag
from hubbeam.identification.spectra import (
    decay_modal_test,
    free_decay,
    frequency_response_estimate,
    periodic_chirp,
)
from hubbeam.model.beam import beam_from_config
from hubbeam.model.drive import QUANSER_SRV02
from hubbeam.model.maneuvers import SensorSpec

#: the rig's link and hub (the configuration's ``beam`` section)
RIG_BEAM = {"length": 0.6, "rhoA": 0.135, "EI": 1.15, "EA": 3.45e6, "hub_inertia": 0.0021, "hub_radius": 0.0}
#: the nominal case (a configuration's ``cases.rig``; the maneuver is replaced by each experiment's)
RIG_CASE = {
    "model": "CFOAM", "modes": 3, "t_end": 1.0,
    "maneuver": {"kind": "voltage_table", "time": [0.0, 1.0], "voltage": [0.0, 0.0]},
    "drive": QUANSER_SRV02.to_dict(),
    "root_spring": {"stiffness": 30.0, "damping": 0.002, "clamp_inertia": 1.0e-5},
    "tip_mass": {"mass": 0.015, "position": 0.57, "inertia": 5.0e-7, "offset": 0.0},
    "damping": {"kind": "modal", "axial": 0.01, "transverse": 0.02},
}
#: the integrator settings of the rig's runs
RIG_NUMERICS = {"rtol": 1e-7, "atol": 1e-10, "output_step": 0.002, "max_steps": 10_000_000,
                "step_warning": 10_000_000, "divergence_limit": 1.0, "quadrature_points": 32, "modes": 3}
#: the true plant: these parameters applied to the nominal case
TRUTH = {"root_spring.stiffness": 27.5, "beam.EI_factor": 0.96, "damping.transverse": 0.015,
         "drive.motor_constant_factor": 0.93, "drive.viscous_friction": 0.012}
#: the rig's sensors: encoder (2 pi / 4096 rad, counting edges), strain gauge on the deflection
#: angle (noise, 12 bits over +-0.2 rad), accelerometer at the tip
SENSORS = {
    "hub_angle": SensorSpec("hub_angle", quantum=2.0 * math.pi / 4096, mode="edges"),
    "deflection_angle": SensorSpec("deflection_angle", noise=2.0e-4, quantum=0.4 / 4096),
    "tip_acceleration": SensorSpec("tip_acceleration", noise=0.02),
}
#: relative standard errors of a tap test's modal fit
TAP_FREQUENCY_ERROR, TAP_DAMPING_ERROR = 0.003, 0.1
#: the cut-off (Hz) that keeps the first mode of the free oscillation (3.1 Hz; the second is at 22 Hz)
DECAY_LOWPASS = 10.0


def rig_case(case: Mapping | None = None, numerics: Mapping | None = None):
    """``(case, beam, numerics)`` of the nominal rig (or of ``case`` / ``numerics`` given as
    mappings), checked by the configuration's one pass (``simulation_settings``)."""
    beam = beam_from_config(RIG_BEAM)
    resolved, settings = simulation_settings({"name": "rig", **(case or RIG_CASE)}, numerics or RIG_NUMERICS, beam.L)
    return resolved, beam, settings


def rig_plant(**options) -> CasePlant:
    """The :class:`CasePlant` of :func:`rig_case`."""
    return CasePlant(*rig_case(**options))


def quantise(value, quantum: float, mode: str):
    """``value`` on the grid of ``quantum`` as the sampled loop's sensors (``hubbeam.core.sampled.quantised``):
    rounded, or counted down to the edge below (``edges``)."""
    if quantum <= 0.0:
        return np.asarray(value, dtype=float)
    shift = 0.0 if mode == "edges" else 0.5
    return quantum * np.floor(np.asarray(value, dtype=float) / quantum + shift)


def read_by(sensor: SensorSpec, values: np.ndarray, rng: np.random.Generator, step: float) -> np.ndarray:
    """The sensor's readings of the physical ``values`` sampled every ``step``: gain and offset, the
    analog low-pass (a first-order lag, exact for values linear between samples), noise, quantisation."""
    reading = sensor.gain * np.asarray(values, dtype=float) + sensor.offset
    if sensor.lowpass > 0.0:
        reading = first_order_lag(reading, step, sensor.lowpass)
    return quantise(reading + sensor.noise * rng.standard_normal(reading.size), sensor.quantum, sensor.mode)


def modal_test(plant: CasePlant, truth: Mapping[str, float], hub: str, modes: int, rng: np.random.Generator,
               name: str, frequency_error: float = TAP_FREQUENCY_ERROR,
               damping_error: float = TAP_DAMPING_ERROR) -> ModalTest:
    """The first ``modes`` bending modes of the true plant, hub ``held`` or ``free``, with relative
    Gaussian errors (standard deviations ``frequency_error``, ``damping_error``), stated as the
    file's uncertainties."""
    frequency, zeta = (values[:modes] for values in plant.modes(truth, hub))
    return ModalTest(name=name, hub=hub, mode=np.arange(1, modes + 1),
                     frequency=frequency * (1.0 + frequency_error * rng.standard_normal(modes)),
                     frequency_std=frequency_error * frequency,
                     damping_ratio=zeta * (1.0 + damping_error * rng.standard_normal(modes)),
                     damping_ratio_std=damping_error * zeta, source="synthetic modal test")


def free_oscillation(plant: CasePlant, truth: Mapping[str, float], rng: np.random.Generator, t_end: float = 3.0,
                     step: float = 0.002, deflection: float = 0.015,
                     sensor: SensorSpec = SENSORS["deflection_angle"]) -> tuple[np.ndarray, np.ndarray]:
    """``(time, reading)``: the hub held and the link released from a tip deflection ``deflection``
    (m) in the shape a force at the tip gives the clamped link (``q2`` along ``K2^-1 f2(L)``), read
    by ``sensor`` (a deflection angle's) every ``step`` s."""
    _, _, sm = plant.system(truth, drive=False)
    shape = np.linalg.solve(sm.K2, sm.f2L)
    q2 = deflection * shape / (sm.f2L @ shape)
    run = plant.release(truth, q2, t_end, step, [sensor.signal])
    return run["time"], read_by(sensor, run[sensor.signal], rng, step)


def doublet(duration: float, step: float, amplitude: float, width: float, start: float = 0.1):
    """``(time, command)``: ``amplitude`` for ``width`` s from ``start``, then ``-amplitude`` for as
    long (a rest-to-rest move of the hub), zero otherwise."""
    t = np.arange(int(round(duration / step)) + 1) * step
    command = np.where((t >= start) & (t < start + width), amplitude, 0.0)
    return t, command - np.where((t >= start + width) & (t < start + 2.0 * width), amplitude, 0.0)


def smooth_move(duration: float, step: float, angle: float, start: float, length: float):
    """``(time, reference)``: a hub-angle reference rising smoothly (a cosine) by ``angle`` rad over
    ``length`` s from ``start``."""
    t = np.arange(int(round(duration / step)) + 1) * step
    ramp = np.clip((t - start) / length, 0.0, 1.0)
    return t, angle * 0.5 * (1.0 - np.cos(math.pi * ramp))


def measured(plant: CasePlant, truth: Mapping[str, float], name: str, time: np.ndarray, signals: Sequence[str],
             rng: np.random.Generator, command: np.ndarray | None = None, loop: PdLoop | None = None,
             reference: np.ndarray | None = None, excitation: str = "pulse",
             sensors: Mapping[str, SensorSpec] = SENSORS) -> TimeSeries:
    """The time series the rig's ``sensors`` record of the true plant driven by the voltage
    ``command``, or inside ``loop`` following ``reference`` (the recorded command is then the loop's)."""
    chosen = {signal: sensors[signal] for signal in signals}
    template = TimeSeries(name=name, input="voltage", time=time, command=command,
                          signals={signal: np.zeros(time.size) for signal in signals}, sensors=chosen,
                          excitation=excitation, loop=loop, reference=reference)
    simulated = plant.simulate(truth, template, command=loop is not None)
    step = template.step
    readings = {signal: read_by(chosen[signal], simulated[signal], rng, step) for signal in signals}
    return TimeSeries(name=name, input="voltage", time=time,
                      command=simulated["command"] if loop is not None else command, signals=readings,
                      sensors=chosen, excitation=excitation, loop=loop, reference=reference,
                      source="synthetic time series")


def sweep_responses(plant: CasePlant, truth: Mapping[str, float], rng: np.random.Generator, segment: int = 4096,
                    periods: int = 6, step: float = 0.002,
                    band: tuple[float, float] = (1.0, 60.0), amplitude: float = 0.5,
                    ) -> tuple[TimeSeries, list[FrequencyResponse]]:
    """A periodic swept sine of 0.3 to 80 Hz of ``amplitude`` V
    (:func:`~hubbeam.identification.spectra.periodic_chirp`; at 0.5 V the link responds linearly to
    the accelerometer's accuracy, at 1.5 V its acceleration near the second mode is 1.4 % off the
    linear response) of ``periods`` periods of ``segment`` samples on the true plant, and the H1 estimates to the
    deflection angle and the tip acceleration over ``band`` (Hz) from every period but the first
    two (the transient of the first mode, whose time constant is 4.6 s), rectangular window, no
    overlap."""
    t, command = periodic_chirp(segment, periods, step, 0.3, 80.0, amplitude)
    series = measured(plant, truth, "sweep", t, ["deflection_angle", "tip_acceleration"], rng, command=command,
                      excitation="swept_sine")
    return series, [frequency_response_estimate(series, output, segment, overlap=0.0, window="boxcar", band=band,
                                                skip=2 * segment, name=f"frf_{short}")
                    for output, short in (("deflection_angle", "deflection"), ("tip_acceleration", "acceleration"))]


def rig_dataset(output: Path, seed: int) -> dict[str, Path]:
    """Write the shipped data set into the folder ``output`` (module docstring); the files by name."""
    output.mkdir(parents=True, exist_ok=True)
    plant = rig_plant()
    streams = [np.random.default_rng(child) for child in np.random.SeedSequence(seed).spawn(6)]
    experiments = {
        "tap_held": modal_test(plant, TRUTH, "held", 3, streams[0], "tap_held"),
        "tap_free": modal_test(plant, TRUTH, "free", 2, streams[1], "tap_free"),
    }
    time, reading = free_oscillation(plant, TRUTH, streams[2])
    decay = free_decay(time, reading, lowpass=DECAY_LOWPASS)
    experiments["held_decay"] = decay_modal_test(decay, "held_decay")
    _, responses = sweep_responses(plant, TRUTH, streams[3])
    experiments |= {response.name: response for response in responses}
    t, command = doublet(3.0, 0.002, 1.5, 0.2)
    experiments["pulse"] = measured(plant, TRUTH, "pulse", t, ["hub_angle", "deflection_angle"], streams[4],
                                    command=command)
    t, reference = smooth_move(3.0, 0.002, 0.5, 0.2, 0.4)
    experiments["pd_step"] = measured(plant, TRUTH, "pd_step", t, ["hub_angle", "deflection_angle"], streams[5],
                                      loop=PdLoop(kp=5.0, kd=0.1), reference=reference, excitation="step")
    note = f"synthetic data of hubbeam.identification.synthetic (seed {seed}); not measured"
    written = {name: write_experiment(experiment, output / f"{name}.csv", (note,))
               for name, experiment in experiments.items()}
    written["held_oscillation"] = write_columns(output / "held_oscillation.csv", {
        "time": ("s", time), "deflection_angle": ("rad", reading)}, (note, "the hub held, the link released"))
    written["synthetic"] = output / "synthetic.json"
    written["synthetic"].write_text(json.dumps({
        "seed": seed, "truth": TRUTH, "nominal_case": RIG_CASE, "beam": RIG_BEAM, "numerics": RIG_NUMERICS,
        "sensors": {name: spec.to_dict() for name, spec in SENSORS.items()},
        "tap_errors": {"frequency": TAP_FREQUENCY_ERROR, "damping_ratio": TAP_DAMPING_ERROR},
        "free_decay": {"frequency_hz": decay.frequency, "damping_ratio": decay.damping_ratio}}, indent=2) + "\n",
        encoding="utf-8")
    return written


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m hubbeam.identification.synthetic",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=Path("studies/identification_rig"),
                        help="folder of the data set (default: %(default)s)")
    parser.add_argument("--seed", type=int, default=20250101, help="seed of every random number (default: %(default)s)")
    args = parser.parse_args(argv)
    for name, path in rig_dataset(args.output, args.seed).items():
        print(f"{name}: {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
