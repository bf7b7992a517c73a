"""A fit as a CF dataset: the parameters with their intervals and correlations, every experiment's
measured and fitted curves and residuals (``hubbeam.results.io.write_netcdf`` writes it).

Dimensions ``parameter`` and ``parameter_j`` (the correlation's columns), ``start`` (the fit's
starting points), ``direction`` (the Jacobian's singular values), and per experiment ``<name>`` its
own: ``<name>_mode`` (a modal test), ``<name>_frequency`` (Hz, a frequency response), ``<name>_time``
(s, a time series), ``<name>_residual_index`` (its weighted residuals). Variables:

* per parameter: ``value``, ``standard_error``, ``lower_95``, ``upper_95`` (NaN without an
  interval), ``lower_bound``, ``upper_bound``, ``start_value``, ``identifiable`` (a CF flag, 1 or 0)
  and ``reason`` (text, empty when identifiable); the units of each parameter are the coordinate
  ``parameter_units`` (the values of one variable have several units), its long name
  ``parameter_long_name``; ``correlation`` (``parameter``, ``parameter_j``), ``start_cost``,
  ``start_point`` (``start``, ``parameter``), ``singular_value`` (``direction``);
* a modal test: ``<name>_frequency_measured``, ``_std``, ``_fitted`` (Hz), and the damping ratios
  likewise when measured;
* a frequency response: ``<name>_magnitude_measured`` and ``_fitted`` (the response's unit),
  ``<name>_phase_measured`` and ``_fitted`` (degree, in ``(-180, 180]``), ``<name>_standard_error``
  (of ``ln |H|`` and of the phase in rad) and ``<name>_coherence`` when measured;
* a time series: ``<name>_<input>`` (the command), ``<name>_reference`` (a loop's hub-angle
  reference) and per signal ``<name>_<signal>_measured`` and ``_fitted`` (the sensor's reading, the
  signal's unit times its gain);
* every experiment: ``<name>_residual``, the weighted residuals (1).

Each experiment's variables carry the attributes ``experiment``, ``experiment_kind`` and
``experiment_role`` (``fitted`` or ``held_out``); the global attributes hold the provenance
(``hubbeam.results.provenance``), the case, the cost, ``s2`` and ``dof``, the thresholds of the
identifiability tests and, as JSON, every experiment's kind, role, source and errors
(``experiments``).
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.identification.experiments import Experiment, FrequencyResponse, ModalTest
from hubbeam.identification.fit import AT_BOUND, CONFIDENCE, CORRELATED, SINGULAR, FitResult, Validation
from hubbeam.linear.statespace import INPUT_UNITS, OUTPUTS
from hubbeam.results.provenance import global_attributes

#: the values of ``identifiable`` and their meanings (CF flags)
FLAGS = {"flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "not_identifiable identifiable"}


def _attrs(units: str, long_name: str, experiment: Experiment | None = None, role: str = "") -> dict:
    attrs = {"units": units, "long_name": long_name}
    if experiment is not None:
        attrs |= {"experiment": experiment.name, "experiment_kind": experiment.kind, "experiment_role": role}
    return attrs


def _experiment_variables(experiment: Experiment, found: Validation, role: str) -> tuple[dict, dict]:
    """The coordinates and variables of one experiment (module docstring)."""
    name, values = experiment.name, found.prediction.values
    coords, data = {}, {}

    def add(key, dim, array, units, long_name):
        data[f"{name}_{key}"] = (dim, np.asarray(array), _attrs(units, long_name, experiment, role))

    if isinstance(experiment, ModalTest):
        dim = f"{name}_mode"
        coords[dim] = (dim, experiment.mode, {"long_name": "bending mode number, by ascending frequency",
                                              "units": "1"})
        add("frequency_measured", dim, experiment.frequency, "Hz", "measured natural frequency")
        add("frequency_std", dim, experiment.frequency_std, "Hz", "standard uncertainty of the measured frequency")
        add("frequency_fitted", dim, values["frequency"], "Hz", "natural frequency of the fitted model")
        if experiment.damping_ratio is not None:
            add("damping_ratio_measured", dim, experiment.damping_ratio, "1", "measured damping ratio")
            add("damping_ratio_std", dim, experiment.damping_ratio_std, "1",
                "standard uncertainty of the measured damping ratio")
            add("damping_ratio_fitted", dim, values["damping_ratio"], "1", "damping ratio of the fitted model")
    elif isinstance(experiment, FrequencyResponse):
        dim = f"{name}_frequency"
        coords[dim] = (dim, experiment.frequency, {"long_name": "frequency", "units": "Hz"})
        what = f"{experiment.output} per {experiment.input}"
        for label, response in (("measured", experiment.response), ("fitted", values["response"])):
            add(f"magnitude_{label}", dim, np.abs(response), experiment.unit, f"{label} magnitude of {what}")
            add(f"phase_{label}", dim, np.degrees(np.angle(response)), "degree", f"{label} phase of {what}")
        add("standard_error", dim, experiment.standard_error(), "1",
            "standard error of ln|H| and of the phase (rad) from the coherence")
        if experiment.coherence is not None:
            add("coherence", dim, experiment.coherence, "1", "magnitude-squared coherence of the estimate")
    else:
        dim = f"{name}_time"
        coords[dim] = (dim, experiment.time, {"long_name": "time of the sample", "units": "s"})
        if experiment.command is not None:
            add(experiment.input, dim, experiment.command, INPUT_UNITS[experiment.input],
                f"{experiment.input} (the input{' the loop computed' if experiment.loop else ''})")
        if experiment.reference is not None:
            add("reference", dim, experiment.reference, "rad", "hub-angle reference of the loop")
        for signal, measured in experiment.signals.items():
            units = OUTPUTS[signal][0]
            add(f"{signal}_measured", dim, measured, units, f"measured {signal} (sensor reading)")
            add(f"{signal}_fitted", dim, values[signal], units, f"{signal} read by the sensor from the fitted model")
    residual = f"{name}_residual_index"
    coords[residual] = (residual, np.arange(found.residuals.size), {"long_name": "index of the residual",
                                                                     "units": "1"})
    add("residual", residual, found.residuals, "1", "residual over its standard uncertainty")
    return coords, data


def fit_dataset(result: FitResult, experiments: Mapping[str, Experiment]) -> xr.Dataset:
    """The dataset of ``result`` (module docstring); ``experiments`` by name, the fitted and the
    held-out ones."""
    keys = list(result.keys)
    kinds = [parameter.kind for parameter in result.parameters]
    coords = {
        "parameter": ("parameter", keys, {"long_name": "configuration key of the free parameter"}),
        "parameter_j": ("parameter_j", keys, {"long_name": "configuration key of the free parameter (columns)"}),
        "parameter_units": ("parameter", [kind.unit for kind in kinds], {"long_name": "units of the parameter"}),
        "parameter_long_name": ("parameter", [kind.long_name for kind in kinds],
                                {"long_name": "what the parameter is"}),
        "start": ("start", np.arange(result.start_costs.size), {"long_name": "starting point", "units": "1"}),
        "direction": ("direction", np.arange(result.singular_values.size),
                      {"long_name": "singular direction of the scaled Jacobian", "units": "1"}),
    }
    per_unit = "in the parameter's units (parameter_units)"
    data = {
        "value": ("parameter", result.value, {"long_name": f"fitted value, {per_unit}"}),
        "standard_error": ("parameter", result.standard_error, {"long_name": f"standard error, {per_unit}"}),
        "lower_95": ("parameter", result.lower_95, {"long_name": f"lower end of the {CONFIDENCE:.0%} interval"}),
        "upper_95": ("parameter", result.upper_95, {"long_name": f"upper end of the {CONFIDENCE:.0%} interval"}),
        "lower_bound": ("parameter", [p.lower for p in result.parameters], {"long_name": "lower bound of the fit"}),
        "upper_bound": ("parameter", [p.upper for p in result.parameters], {"long_name": "upper bound of the fit"}),
        "start_value": ("parameter", [p.start for p in result.parameters], {"long_name": "given start"}),
        "identifiable": ("parameter", result.identifiable.astype(np.int8),
                         {"long_name": "whether the data determine the parameter", **FLAGS}),
        "reason": ("parameter", list(result.reason), {"long_name": "why the parameter is not identifiable"}),
        "correlation": (("parameter", "parameter_j"), result.correlation,
                        {"units": "1", "long_name": "correlation of the estimates"}),
        "start_cost": ("start", result.start_costs, {"units": "1", "long_name": "cost reached from the start"}),
        "start_point": (("start", "parameter"), result.start_points, {"long_name": f"starting point, {per_unit}"}),
        "singular_value": ("direction", result.singular_values,
                           {"units": "1", "long_name": "singular value of the Jacobian scaled to the bounds"}),
    }
    summary = []
    for role, found in (("fitted", result.fitted), ("held_out", result.validations)):
        for name, validation in found.items():
            experiment = experiments[name]
            more_coords, more_data = _experiment_variables(experiment, validation, role)
            coords |= more_coords
            data |= more_data
            summary.append({"name": name, "kind": experiment.kind, "role": role, "source": experiment.source,
                            "rms_weighted_residual": validation.rms_weighted, "error": validation.error})
    attrs = global_attributes(f"hubbeam identification of case {result.case}", extra={
        "case": result.case, "cost": result.cost, "s2": result.s2, "dof": result.dof,
        "confidence": CONFIDENCE, "at_bound_fraction": AT_BOUND, "singular_ratio": SINGULAR,
        "correlation_limit": CORRELATED, "evaluations": result.evaluations, "fit_seconds": result.seconds,
        "optimizer_message": result.message, "experiments": json.dumps(summary)})
    return xr.Dataset(data, coords=coords, attrs=attrs)


__all__ = ["FLAGS", "fit_dataset"]
