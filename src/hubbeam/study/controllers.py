"""The study report's section on sampled controllers, every number read from the results.

:func:`controllers_markdown` writes the section from the runs (simulation datasets by case), the
sample-time sweep and the robustness maps of the ``control`` section (their datasets, when the
study has them) and the exported controllers' files. It keeps two questions apart:

* **prediction**: how well the design's own model predicts the loop on the truth. The design
  predicts its sampled closed-loop poles (the run's ``controller_poles_real``/``_imag``); the
  truth's linear loop (the robustness map's nominal point) has its own spectral radius. A design
  predicts well when both agree on stability; the gap of the spectral radii says by how much.
* **performance**: what the nonlinear run on the truth does: the hub angle's final error against
  the reference's last angle, the peak and residual tip deflection after the move, the largest
  applied voltage and whether it saturated.

Held-hub frequencies come from the runs whose hub is held still (a prescribed speed table of
zeros: a decaying sinusoid fitted to the tip deflection, :func:`hubbeam.results.measures.fit_decaying_sinusoid`)
beside the frequency a lumped design was fitted to (the lab's measurement, from the run's
``case_config``); the back-EMF damping ``eta_g Kg^2 eta_m kt km / Rm`` from a run's ``drive``
record (:attr:`hubbeam.model.drive.DcMotor.back_emf_damping`) against its viscous friction.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.model.drive import DcMotor
from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import number
from hubbeam.results import measures
from hubbeam.study.summary import residual


def _config(ds: xr.Dataset) -> dict:
    return json.loads(ds.attrs.get("case_config", "{}"))


def held_runs(runs: Mapping[str, xr.Dataset]) -> dict[str, xr.Dataset]:
    """The runs whose hub is held still: a prescribed speed table of zeros."""
    def held(ds):
        maneuver = _config(ds).get("maneuver", {})
        return maneuver.get("kind") == "speed_table" and not any(maneuver.get("speed", [1.0]))
    return {case: ds for case, ds in runs.items() if held(ds)}


def held_frequency_rows(runs: Mapping[str, xr.Dataset]) -> list[dict]:
    """Per held-hub run the fitted frequency (Hz) and damping ratio of its tip deflection; per
    lumped design the held-hub frequency it was fitted to (the lab's measurement)."""
    rows = []
    for case, ds in held_runs(runs).items():
        t = ds["time"].values
        source = f"model: run {case} ({ds.attrs.get('model', '')}, hub held)"
        try:
            fit = measures.fit_decaying_sinusoid(t, ds["tip_transverse"].values, float(t[0]))
        except ValueError as error:  # a run without an oscillation to fit: said, not a failure
            rows.append({"source": f"{source}: {error}", "frequency_hz": math.nan, "damping": math.nan})
            continue
        rows.append({"source": source, "frequency_hz": fit.omega / (2.0 * math.pi),
                     "damping": fit.decay_rate / math.hypot(fit.decay_rate, fit.omega)})
    measured = sorted({float(design["held_frequency"]) for ds in runs.values()
                       if (design := _config(ds).get("maneuver", {}).get("design", {})).get("held_frequency")})
    rows += [{"source": "measured: the lab's free oscillation (the lumped designs' held_frequency)",
              "frequency_hz": value, "damping": math.nan} for value in measured]
    return rows


def drive_damping(runs: Mapping[str, xr.Dataset]) -> dict | None:
    """The back-EMF damping and the viscous friction of the first run with a drive (N m s/rad)."""
    for ds in runs.values():
        if "drive" in ds.attrs:
            motor = DcMotor(**json.loads(ds.attrs["drive"]))
            return {"back_emf": motor.back_emf_damping, "viscous": motor.viscous_friction,
                    "torque_gain": motor.torque_gain}
    return None


def _predicted_radius(ds: xr.Dataset) -> float:
    real = np.atleast_1d(ds.attrs.get("controller_poles_real", []))
    imag = np.atleast_1d(ds.attrs.get("controller_poles_imag", []))
    return float(np.max(np.hypot(real, imag))) if real.size else math.nan


def performance_rows(runs: Mapping[str, xr.Dataset], robustness: xr.Dataset | None) -> list[dict]:
    """Per sampled run: the prediction (the design's predicted spectral radius, the truth's linear
    one) and the performance of the nonlinear run (module docstring)."""
    rows = []
    truth = ({} if robustness is None else
             dict(zip(map(str, robustness["case"].values), robustness["nominal_radius"].values.tolist())))
    for case, ds in runs.items():
        if "applied" not in ds:
            continue
        reference = _config(ds)["maneuver"]["reference"]
        tip = ds["tip_transverse"].values
        applied = ds["applied"].values
        limit = json.loads(ds.attrs["drive"]).get("voltage_limit", math.inf) if "drive" in ds.attrs else math.inf
        rows.append({
            "case": case, "estimator": ds.attrs.get("controller_kind", ""),
            "predicted_radius": _predicted_radius(ds), "truth_radius": float(truth.get(case, math.nan)),
            "final_error_rad": float(ds["theta"].values[-1]) - float(reference["angle"][-1])
            if "angle" in reference else math.nan,
            "peak_tip_m": measures.peak(tip),
            "residual_tip_m": residual(case, ds),
            "peak_voltage": float(np.max(np.abs(applied))),
            "saturated": bool(np.max(np.abs(applied)) >= limit),
            "status": ds.attrs.get("integrator_status", ""),
        })
    return rows


def _verdict(row: dict) -> str:
    predicted, truth = row["predicted_radius"], row["truth_radius"]
    if not math.isfinite(truth):
        return "no linear truth"
    if (predicted < 1.0) == (truth < 1.0):
        return f"agrees ({'stable' if truth < 1.0 else 'unstable'})"
    said, found = ("stable" if value < 1.0 else "unstable" for value in (predicted, truth))
    return f"wrong: predicted {said}, {found} on the truth"


def _file_name(path: str) -> str:
    return path.rsplit("/", 1)[-1]


def _ms(value: float) -> str:
    return "stable over the grid" if not math.isfinite(value) else f"{number(1e3 * value, 3)} ms"


def sweep_markdown(sweep: xr.Dataset) -> str:
    """The boundary of every design, gain and delay, the modes each design lacks and the confirmation."""
    lines = []
    for design in sweep["design"].values:
        for gain in sweep["gain"].values:
            for delay in sweep["delay"].values:
                at = {"design": design, "gain": gain, "delay": delay}
                boundary = float(sweep["boundary"].sel(at))
                first = sweep.sel(at).isel(sample_time=0)
                lines.append([str(design), str(gain), number(float(delay)), _ms(boundary),
                              str(sweep["boundary_mode"].sel(at).values) if math.isfinite(boundary) else "",
                              f"{number(float(first['spectral_radius']), 5)} ({first['mode'].values})"])
    Ts0 = number(1e3 * float(sweep["sample_time"].values[0]), 3)
    table = markdown_table(("design", "gain", "delay (samples)", "loses stability at Ts", "mode that crosses",
                            f"spectral radius at {Ts0} ms (its mode)"), lines)
    truth = {str(name): float(f) for name, f in zip(sweep["truth_mode"].values, sweep["truth_frequency"].values)
             if f > 0.0 and str(name).startswith("bending")}
    missed = []
    for k, design in enumerate(sweep["design"].values):
        found = sweep["design_frequency"].values[k]
        found = found[np.isfinite(found)]
        lacking = [f"{name} ({number(f, 3)} Hz)" for name, f in truth.items()
                   if not np.any(np.abs(found - f) < 0.25 * f)]
        missed.append(f"* **{design}**: design-model frequencies {', '.join(number(f, 3) for f in found if f < 1e3)}"
                      " Hz; " + (f"lacks the truth's {', '.join(lacking)}." if lacking
                                 else "has every bending mode of the truth."))
    aliasing = [f"{name} at {number(1e3 * float(ts), 3)} ms" for name, ts in
                zip(sweep["truth_mode"].values, sweep["aliasing_sample_time"].values)
                if math.isfinite(ts) and str(name).startswith("bending")]
    text = [table, "", "The truth's bending modes alias (Ts = 1/(2f)) from: " + "; ".join(aliasing) + ".", "",
            "What each design model has of the truth's bending modes "
            f"({', '.join(f'{name} {number(f, 3)} Hz' for name, f in truth.items())}):", "", *missed]
    if "confirmation_sample_time" in sweep:
        settings = json.loads(sweep.attrs["confirmation"])
        text += ["", f"Nonlinear confirmation of the boundary of {settings['case']} ({settings['gain']} gain, delay "
                 f"{number(settings['delay'])}; linear boundary {_ms(settings['boundary'])}): runs on its own model "
                 "from a small tip deflection, the reference at rest; growth rate of the applied voltage's envelope "
                 "against the linear loop's ln(spectral radius)/Ts.", ""]
        text.append(markdown_table(
            ("run", "Ts (ms)", "spectral radius", "predicted rate (1/s)", "measured rate (1/s)", "integrator"),
            ([str(run), number(1e3 * float(sweep["confirmation_sample_time"].sel(run=run)), 4),
              number(float(sweep["confirmation_radius"].sel(run=run)), 5),
              number(float(sweep["confirmation_predicted_rate"].sel(run=run)), 3),
              number(float(sweep["confirmation_measured_rate"].sel(run=run)), 3),
              str(sweep["confirmation_status"].sel(run=run).values)] for run in sweep["run"].values)))
    return "\n".join(text)


def robustness_markdown(robustness: xr.Dataset) -> str:
    """The stable range of every parameter per case, against the range swept."""
    names = [name.removeprefix("radius_") for name in robustness.data_vars if name.startswith("radius_")]
    lines = []
    for case in robustness["case"].values:
        cells = [str(case), number(float(robustness["nominal_radius"].sel(case=case)), 5)]
        for name in names:
            grid = robustness[f"{name}_value"].values
            low, high = (float(robustness[f"{side}_{name}"].sel(case=case)) for side in ("lowest", "highest"))
            if not math.isfinite(low):
                cells.append("unstable at nominal")
                continue
            ends = ["" if math.isclose(low, grid[0]) else "*", "" if math.isclose(high, grid[-1]) else "*"]
            cells.append(f"{number(low, 3)}{ends[0]} .. {number(high, 3)}{ends[1]}")
        lines.append(cells)
    def heading(name):
        grid = robustness[f"{name}_value"]
        return (f"{name} ({grid.attrs.get('units', '')}; swept {number(float(grid.values[0]), 3)}.."
                f"{number(float(grid.values[-1]), 3)})")

    header = ["case", "spectral radius at nominal"] + [heading(name) for name in names]
    text = (markdown_table(header, lines) + "\n\nEach cell: the range around the nominal value in which the loop "
            "stays stable; * marks a boundary inside the swept range (Brent's method), no mark the range's end.")
    if robustness.sizes.get("confirmation", 0):
        runs = robustness[[name for name in robustness.data_vars if name.startswith("confirmation_")]]
        text += ("\n\nNonlinear confirmation of the margins inside their ranges: the case's nominal controller on "
                 "the moved plant, from a small tip deflection, the reference at rest, sensors without noise and "
                 "quantisation; growth rate of the applied voltage's envelope against the linear ln(spectral "
                 "radius)/Ts.\n\n" + markdown_table(
                     ("case", "parameter", "margin", "run", "value", "spectral radius", "predicted rate (1/s)",
                      "measured rate (1/s)", "integrator"),
                     ([str(run["confirmation_case"].values), str(run["confirmation_parameter"].values),
                       str(run["confirmation_side"].values), str(run["confirmation_where"].values),
                       number(float(run["confirmation_value"]), 4), number(float(run["confirmation_radius"]), 6),
                       number(float(run["confirmation_predicted_rate"]), 3),
                       number(float(run["confirmation_measured_rate"]), 3), str(run["confirmation_status"].values)]
                      for run in (runs.isel(confirmation=k) for k in range(runs.sizes["confirmation"])))))
    return text


def controllers_markdown(runs: Mapping[str, xr.Dataset], sweep: xr.Dataset | None = None,
                         robustness: xr.Dataset | None = None,
                         exports: Mapping[str, tuple[str, str]] | None = None,
                         figures: Mapping[str, str] | None = None) -> str:
    """The section (module docstring); ``exports`` the exported files (paths relative to the report)
    by case; ``figures`` the PNGs of the sample-time sweep (``sample_time_sweep``) and the robustness
    maps (``robustness``) by product key. Empty without sampled runs, held-hub runs or analyses."""
    figures = figures or {}

    def figure(key: str) -> list[str]:
        return [f"![{key}]({figures[key]})", ""] if key in figures else []

    held = held_frequency_rows(runs)
    drive = drive_damping(runs)
    performance = performance_rows(runs, robustness)
    if not (held or performance or sweep is not None or robustness is not None):
        return ""
    parts = ["## Sampled controllers", ""]
    if held:
        parts += ["### Held-hub frequency", "", markdown_table(
            ("source", "frequency (Hz)", "damping ratio"),
            ([row["source"], number(row["frequency_hz"], 4), number(row["damping"], 3)] for row in held)), ""]
    if drive is not None:
        ratio = drive["back_emf"] / drive["viscous"] if drive["viscous"] > 0 else math.inf
        parts += ["### The drive's damping", "",
                  f"The motor's back-EMF damps the hub with eta_g Kg^2 eta_m kt km / Rm = "
                  f"{number(drive['back_emf'], 3)} N m s/rad, {number(ratio, 3)} times the hub's viscous friction "
                  f"Beq = {number(drive['viscous'], 3)} N m s/rad (torque gain "
                  f"{number(drive['torque_gain'], 3)} N m/V; from the runs' drive record).", ""]
    if performance:
        parts += ["### Prediction: does the design's model predict the loop on the truth?", "",
                  "The design's predicted spectral radius (its own sampled loop) against the truth's (the loop "
                  "with the truth's linear model, the robustness map's nominal point).", "",
                  markdown_table(("case", "controller", "predicted max|z|", "truth max|z|", "prediction"),
                                 ([row["case"], row["estimator"], number(row["predicted_radius"], 6),
                                   number(row["truth_radius"], 6), _verdict(row)] for row in performance)), "",
                  "### Performance: the nonlinear runs on the truth", "",
                  "Residual: the largest |v(L)| after the command ends (the reference's last time), as in the "
                  "table of the cases.", "",
                  markdown_table(("case", "final hub-angle error (rad)", "peak v(L) (m)", "residual v(L) (m)",
                                  "peak voltage (V)", "saturated", "integrator"),
                                 ([row["case"], number(row["final_error_rad"], 3), number(row["peak_tip_m"], 3),
                                   number(row["residual_tip_m"], 3), number(row["peak_voltage"], 3),
                                   "yes" if row["saturated"] else "no", row["status"]] for row in performance)), ""]
    if sweep is not None:
        parts += ["### Sample time: where each design loses stability", "", sweep_markdown(sweep), "",
                  *figure("sample_time_sweep")]
    if robustness is not None:
        parts += ["### Robustness margins", "", robustness_markdown(robustness), "", *figure("robustness")]
    if exports:
        parts += ["### Exported controllers", "", "The sampled controller and the design's discrete plant of every "
                  "sampled case (hubbeam.control.implementation), for MATLAB/Simulink or python-control:", "",
                  *(f"* {case}: [{_file_name(mat)}]({mat}), [{_file_name(text)}]({text})"
                    for case, (mat, text) in exports.items()), ""]
    return "\n".join(parts)
