"""Tip deflection of the assumed-mode models against the Exudyn ANCF reference.

For each validation case (a prescribed spin-up of Eq. 43, optionally with a tip mass) the models
(FOAM, CFOAM, TLAM) are simulated with :func:`hubbeam.simulation.simulate.simulate` and compared with
:func:`hubbeam.validation.exudyn_model.spin_up` on the same uniform time grid. Metrics
(:func:`tip_metrics`, :func:`comparison_table`): the largest absolute difference of the tip
deflection over the run, the peak ``max |v|`` and the residual amplitude ``max |v|`` for ``t >
tf`` (after the spin-up), of the model and of the reference. A model that diverged (TLAM beyond its
critical speed) has NaN outputs after ``diverged_at_s``; its metrics cover the span before that.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from hubbeam.configuration.sections import ValidationCase
from hubbeam.configuration.settings import Case, Numerics
from hubbeam.model.parameters import TipMass
from hubbeam.results import measures
from hubbeam.simulation.simulate import simulate

#: reference label in tables and figures
REFERENCE = "Exudyn"


def model_case(validation_case: ValidationCase, model: str, modes: int, beam_length: float) -> Case:
    """The simulation case of ``model`` with ``modes`` modes on the validation case (no tip mass: a
    mass of 0 at the tip)."""
    return Case(name=f"validation_{validation_case.name}_{model}", model=model, maneuver=validation_case.maneuver,
                t_end=float(validation_case.t_end), modes=int(modes),
                tip_mass=validation_case.tip_mass or TipMass(mass=0.0, position=float(beam_length)))


def simulate_models(validation_case: ValidationCase, models: Sequence[str], params, numerics: Numerics) -> xr.Dataset:
    """Tip outputs of every model for one validation case, stacked along ``model``."""
    runs = []
    for model in models:
        ds = simulate(model_case(validation_case, model, numerics.modes, params.L), params, numerics)
        runs.append(xr.Dataset(
            {
                "tip_transverse": ds["tip_transverse"],
                "tip_axial_total": (ds["tip_axial"] + ds["tip_foreshortening"]).assign_attrs(
                    units="m", long_name="tip axial displacement w1(L) + wc(L)"),
                "diverged": ((), int(ds.attrs["diverged"]),
                             {"units": "1", "long_name": "1 if the run diverged (hubbeam.model.validity)"}),
                "diverged_at_s": ((), float(ds.attrs["diverged_at_s"]),
                                  {"units": "s", "long_name": "time of divergence (NaN: none)"}),
                "n_steps": ((), int(ds.attrs["n_steps"]),
                            {"units": "1", "long_name": "accepted Radau IIA steps"}),
            },
            coords={"time": ds["time"]},
        ).expand_dims(model=[model]))
    combined = xr.concat(runs, dim="model")
    combined["model"].attrs.update(long_name="hubbeam model", units="1")
    combined.attrs = {"case": validation_case.name, "n_modes": int(numerics.modes),
                      "case_config": json.dumps(validation_case.to_dict(), sort_keys=True)}
    return combined


def tip_metrics(time: np.ndarray, deflection: np.ndarray, tf: float) -> dict:
    """Peak ``max |v|`` (and its time) and residual amplitude ``max |v|`` for ``t > tf``
    (:mod:`hubbeam.results.measures`).

    NaN samples (after a divergence) are ignored; a residual over no finite sample is NaN.
    """
    return {
        "peak": measures.peak(deflection),
        "peak_time": measures.peak_time(time, deflection),
        "residual": measures.residual_amplitude(time, deflection, tf),
    }


def comparison_dataset(reference: xr.Dataset, models: xr.Dataset) -> xr.Dataset:
    """Reference and model tip deflections of one case on the common grid, with differences."""
    if reference.sizes["time"] != models.sizes["time"] or not np.allclose(
            reference["time"].values, models["time"].values, rtol=0.0, atol=1e-9):
        raise ValueError(f"case {models.attrs.get('case')!r}: the Exudyn and model time grids "
                         "differ; allowed: the same t_end and output step")
    ds = models.copy()
    ds["tip_transverse_reference"] = ("time", reference["tip_transverse"].values,
                                      dict(reference["tip_transverse"].attrs))
    ds["tip_axial_reference"] = ("time", reference["tip_axial"].values,
                                 dict(reference["tip_axial"].attrs))
    ds["theta_reference"] = ("time", reference["theta"].values, dict(reference["theta"].attrs))
    ds["difference"] = (ds["tip_transverse"] - ds["tip_transverse_reference"]).assign_attrs(
        units="m", long_name="tip deflection of the model minus the Exudyn reference")
    ds.attrs = {"case": models.attrs["case"], "n_modes": int(models.attrs["n_modes"]),
                "case_config": models.attrs["case_config"],
                **{f"reference_{key}": value for key, value in reference.attrs.items()
                   if key.startswith("exudyn_") or key == "model"}}
    return ds


def comparison_table(datasets: Mapping[str, xr.Dataset]) -> pd.DataFrame:
    """One row per (case, model): differences, peaks and residual amplitudes (SI units)."""
    rows = []
    for name, ds in datasets.items():
        config = json.loads(ds.attrs["case_config"])
        tf = float(config["maneuver"]["tf"])
        tip = config.get("tip_mass") or {"mass": 0.0}
        time = ds["time"].values
        reference = tip_metrics(time, ds["tip_transverse_reference"].values, tf)
        for model in ds["model"].values:
            run = ds.sel(model=model)
            ours = tip_metrics(time, run["tip_transverse"].values, tf)
            difference = measures.peak(run["difference"].values)
            rows.append({
                "case": name, "model": str(model),
                "wf": float(config["maneuver"]["wf"]), "tf": tf,
                "tip_mass_kg": float(tip["mass"]),
                "n_modes": int(ds.attrs["n_modes"]),
                "max_abs_difference_m": difference,
                "max_abs_difference_rel_peak": difference / reference["peak"],
                "peak_m": ours["peak"], "peak_reference_m": reference["peak"],
                "peak_time_s": ours["peak_time"], "peak_time_reference_s": reference["peak_time"],
                "residual_m": ours["residual"], "residual_reference_m": reference["residual"],
                "residual_ratio": ours["residual"] / reference["residual"],
                "diverged": int(run["diverged"]),
                "diverged_at_s": float(run["diverged_at_s"]),
            })
    return pd.DataFrame(rows)


def convergence_table(runs: Mapping[str, xr.Dataset], production: Mapping) -> pd.DataFrame:
    """Exudyn convergence: each study varies one setting from ``production``.

    ``runs`` maps a label to a :func:`~hubbeam.validation.exudyn_model.spin_up` dataset whose
    attributes carry its settings. For each study (``elements``, ``time_step``,
    ``newton_tolerance``) the finest run is the reference; every run gets the largest tip
    deflection difference to it and to the next finer run, and its peak and residual.
    """
    larger_is_finer = {"elements": True, "time_step": False, "newton_tolerance": False}
    rows = []
    for study, ascending in larger_is_finer.items():
        members = [ds for ds in runs.values()
                   if all(ds.attrs[f"exudyn_{key}"] == production[key]
                          for key in larger_is_finer if key != study)]
        # coarse to fine
        members.sort(key=lambda ds: ds.attrs[f"exudyn_{study}"], reverse=not ascending)
        if len(members) < 2:
            continue
        finest = members[-1]
        tf = json.loads(finest.attrs["maneuver"])["tf"]
        for index, ds in enumerate(members):
            v = ds["tip_transverse"].values
            finer = (np.max(np.abs(v - members[index + 1]["tip_transverse"].values))
                     if index + 1 < len(members) else np.nan)
            metrics = tip_metrics(ds["time"].values, v, tf)
            rows.append({
                "study": study, "value": ds.attrs[f"exudyn_{study}"],
                "elements": ds.attrs["exudyn_elements"],
                "time_step_s": ds.attrs["exudyn_time_step"],
                "newton_tolerance": ds.attrs["exudyn_newton_tolerance"],
                "production": int(ds.attrs[f"exudyn_{study}"] == production[study]),
                "max_abs_difference_to_finest_m": float(np.max(np.abs(v - finest["tip_transverse"]
                                                                      .values))),
                "max_abs_difference_to_next_finer_m": float(finer),
                "peak_m": metrics["peak"], "residual_m": metrics["residual"],
                "newton_iterations": ds.attrs["exudyn_newton_iterations"],
                "cpu_time_s": ds.attrs["exudyn_cpu_time_s"],
            })
    return pd.DataFrame(rows)


def mode_study(validation_case: ValidationCase, models: Sequence[str], modes: Sequence[int], params,
               numerics: Numerics, reference: xr.Dataset) -> pd.DataFrame:
    """Largest tip-deflection difference to the reference against the number of assumed modes.

    A difference that stops changing with the modes is a difference of the models' equations,
    not of their truncation. One row per (model, modes); diverged runs are skipped.
    """
    rows = []
    for model in models:
        for n in modes:
            ds = simulate(model_case(validation_case, model, n, params.L), params,
                          dataclasses.replace(numerics, modes=int(n)))
            if ds.attrs["diverged"]:
                continue
            difference = np.abs(ds["tip_transverse"].values
                                - reference["tip_transverse"].values)
            rows.append({"case": validation_case.name, "model": model, "n_modes": int(n),
                         "max_abs_difference_m": float(np.max(difference)),
                         "max_abs_difference_rel_peak": float(
                             np.max(difference) / np.max(np.abs(reference["tip_transverse"])))})
    return pd.DataFrame(rows)

