"""What the model predicts for each experiment, and the weighted residuals the fit minimises.

For parameter values ``p`` and an experiment, :func:`predict` gives the model's counterpart of every
measured number (through :class:`hubbeam.identification.plant.CasePlant`), and :func:`residuals`
the residuals divided by their standard uncertainty, so that each is about N(0, 1) when the model
and the stated uncertainties are right:

* a modal test (relative frequency error): ``(f_model - f) / sigma_f`` per mode, ``sigma_f`` the
  file's ``frequency_std`` or ``FREQUENCY_UNCERTAINTY f``; with damping ratios also
  ``(zeta_model - zeta) / sigma_zeta``. The modes are the model's bending modes by ascending
  frequency, hub held or free (:meth:`~hubbeam.identification.plant.CasePlant.modes`);
* a frequency response (log-magnitude and phase, weighted by coherence): ``ln |H_model / H|`` (the
  model's response times the input's hold, ``FrequencyResponse.hold_response``) and
  the phase difference wrapped to ``(-pi, pi]``, each over the coherence's standard error
  (``FrequencyResponse.standard_error``); a point of coherence 0 weighs nothing. Fitting the
  logarithm rather than the complex value weighs a resonance and an anti-resonance alike and
  matches the estimate's error, which is relative;
* a time series (signals scaled by their noise): ``(reading_model - reading) / sigma`` per signal
  and sample, ``reading_model = gain x signal + offset`` through the sensor's first-order low-pass
  when it has one (exact for a signal linear between the samples), less half a step for an encoder
  counting ``edges`` (its readings lie that much below the signal on average), ``sigma`` the
  sensor's noise with its quantisation as uniform noise (``TimeSeries.noise``). The sensor's gain and offset are
  the experiment's, or the free parameters ``sensors.<signal>.gain|offset``.

A prediction that cannot be made (a simulation that stopped, a response that is not finite) gives
residuals of :data:`FAILED`, so the fit moves away from it. :func:`check_experiment` refuses an
experiment the case cannot predict, naming what is missing: a voltage without a drive, a mode
number beyond the case's bending modes, a signal without a noise level.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy.signal import lfilter

from hubbeam.identification.experiments import Experiment, FrequencyResponse, ModalTest, TimeSeries
from hubbeam.identification.parameters import sensor_values
from hubbeam.identification.plant import CasePlant

#: the residual of a prediction that could not be made
FAILED = 1e6


class ExperimentMismatch(ValueError):
    """The case cannot predict an experiment; the message names the experiment and what is missing."""


@dataclass(frozen=True, eq=False)
class Prediction:
    """The model's values for an experiment: ``values`` by name, in the measured numbers' shapes
    (``frequency``, ``damping_ratio``; ``response``; each signal's reading)."""

    experiment: str
    values: Mapping[str, np.ndarray]


def check_experiment(plant: CasePlant, experiment: Experiment) -> None:
    """An :class:`ExperimentMismatch` when the case of ``plant`` cannot predict ``experiment``
    (module docstring)."""
    where = f"experiment {experiment.name}"
    case = plant.case
    if getattr(experiment, "input", None) == "voltage" and case.drive is None:
        raise ExperimentMismatch(f"{where}: input voltage, but case {case.label!r} has no drive; allowed: an "
                                 "experiment driven by hub_torque, or a case with a drive section")
    if isinstance(experiment, ModalTest):
        found = plant.modes({}, experiment.hub, experiment.speed)[0].size
        if experiment.mode.max() > found:
            raise ExperimentMismatch(f"{where}: mode {int(experiment.mode.max())}, but case {case.label!r} has "
                                     f"{found} bending modes with the hub {experiment.hub}; allowed: modes 1..{found} "
                                     "(or more modes in the case)")
    if isinstance(experiment, TimeSeries):
        for signal in experiment.signals:
            if experiment.noise(signal) <= 0.0:
                raise ExperimentMismatch(f"{where}.sensors.{signal}: no noise level; allowed: noise > 0 or "
                                         "quantum > 0 (the reading's scatter, e.g. its standard deviation at rest)")


def first_order_lag(values: np.ndarray, step: float, time_constant: float) -> np.ndarray:
    """``values`` (sampled every ``step``, settled at the first) through the analog first-order
    low-pass ``tau y' = x - y``, exactly for ``x`` linear between the samples:
    ``y_k+1 = a y_k + b0 x_k+1 + b1 x_k``, ``a = exp(-h / tau)``, ``b0 = 1 - (tau / h)(1 - a)``,
    ``b1 = (tau / h)(1 - a) - a``."""
    ratio = time_constant / step
    a = math.exp(-1.0 / ratio)
    b0 = 1.0 - ratio * (1.0 - a)
    b1 = ratio * (1.0 - a) - a
    return lfilter([b0, b1], [1.0, -a], values, zi=[values[0] * (1.0 - b0)])[0]


def _reading(series: TimeSeries, signal: str, values: np.ndarray, sensors: Mapping) -> np.ndarray:
    """The sensor's expected reading of the physical ``values`` (module docstring)."""
    spec = series.sensors[signal]
    gain = sensors.get(signal, {}).get("gain", spec.gain)
    offset = sensors.get(signal, {}).get("offset", spec.offset)
    reading = gain * values + offset
    if spec.lowpass > 0.0 and np.all(np.isfinite(reading)):
        reading = first_order_lag(reading, series.step, spec.lowpass)
    return reading - (0.5 * spec.quantum if spec.mode == "edges" else 0.0)


def predict(plant: CasePlant, experiment: Experiment, values: Mapping[str, float]) -> Prediction:
    """The model's counterpart of ``experiment``'s measured numbers with the parameter ``values``."""
    if isinstance(experiment, ModalTest):
        frequency, zeta = plant.modes(values, experiment.hub, experiment.speed)
        index = experiment.mode - 1
        return Prediction(experiment.name, {"frequency": frequency[index], "damping_ratio": zeta[index]})
    if isinstance(experiment, FrequencyResponse):
        response = plant.frequency_response(values, experiment.input, experiment.output, experiment.frequency)
        return Prediction(experiment.name, {"response": response * experiment.hold_response()})
    simulated = plant.simulate(values, experiment)
    sensors = sensor_values(values)
    return Prediction(experiment.name, {signal: _reading(experiment, signal, simulated[signal], sensors)
                                        for signal in experiment.signals})


def weighted_residuals(experiment: Experiment, prediction: Prediction) -> np.ndarray:
    """The residuals of ``prediction`` against ``experiment``, each over its standard uncertainty
    (module docstring); :data:`FAILED` where the prediction is not finite."""
    values = prediction.values
    if isinstance(experiment, ModalTest):
        parts = [(values["frequency"] - experiment.frequency) / experiment.frequency_std]
        if experiment.damping_ratio is not None:
            parts.append((values["damping_ratio"] - experiment.damping_ratio) / experiment.damping_ratio_std)
    elif isinstance(experiment, FrequencyResponse):
        error = experiment.standard_error()
        seen = np.isfinite(error)
        ratio = values["response"][seen] / experiment.response[seen]
        with np.errstate(divide="ignore", invalid="ignore"):
            parts = [np.log(np.abs(ratio)) / error[seen], np.angle(ratio) / error[seen]]
    else:
        parts = [(values[signal] - experiment.signals[signal]) / experiment.noise(signal)
                 for signal in experiment.signals]
    found = np.concatenate(parts)
    return np.where(np.isfinite(found), found, FAILED)


def residuals(plant: CasePlant, experiment: Experiment, values: Mapping[str, float]) -> np.ndarray:
    """:func:`weighted_residuals` of :func:`predict`."""
    return weighted_residuals(experiment, predict(plant, experiment, values))


__all__ = ["FAILED", "ExperimentMismatch", "Prediction", "check_experiment", "first_order_lag", "predict", "residuals",
           "weighted_residuals"]
