"""How far a controller designed on one model may be trusted on another: the measures of every
``state_feedback`` run whose gains were designed by LQR (``maneuver.design``), and the verdict.

Per run (:func:`closed_loop_measures`), from the tip deflection v(L) and the hub torque after
the reference's spin-up ends at ``tf``: the peak ``max |v(L)|`` over the run, the residual
vibration ``max |v(L)|`` after ``tf``, the settling time of v(L) (from ``tf`` until ``|v(L)|``
stays inside :data:`SETTLING_BAND` of its peak; NaN if it never does before the run ends), the
peak torque, and whether the loop stayed stable (the run ended normally with a bounded response).

The runs pair up by design model and design speed (:func:`design_table`): the design's own
closed loop (the controller on the model it was designed on) is its prediction, and the run on
the reference model (:data:`REFERENCE_MODEL`, the most complete) is the truth. A design is *good
enough* at a speed when the reference loop is stable and its peak and residual tip deflections
differ from the prediction by at most :data:`TRUST_TOLERANCE` (relative); :func:`verdicts`
states, per design model, the first speed where it stops being good enough and by how much, and
the first speed where its loop on the reference model is unstable. That is the question of
*prediction*; :func:`performance` answers the other one, how the design does on the reference
model against the other designs at the same speed (residual vibration): a design may predict
poorly and still leave the least vibration.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.reporting.products import REFERENCE_MODEL
from hubbeam.results import measures
from hubbeam.results.reader import attr, maneuver, model, times, variable
from hubbeam.study.summary import residual

#: the settling band of v(L), a fraction of its peak
SETTLING_BAND = 0.05
#: the largest relative gap between prediction and reference that is still good enough
TRUST_TOLERANCE = 0.10
#: residual vibrations within this relative difference of the least are tied for the least
#: (SFOAM's and FOAM's designs leave residuals equal to two figures)
TIE = 0.01
#: the measures of a run, in the order of the report's table
MEASURES = ("peak_tip_deflection_m", "residual_vibration_m", "settling_time_s", "peak_torque_Nm")


def is_designed(case: str, ds: xr.Dataset) -> bool:
    """Whether ``case`` ran a state feedback designed by LQR."""
    found = maneuver(case, ds)
    return found["kind"] == "state_feedback" and "design" in found


def closed_loop_measures(case: str, ds: xr.Dataset) -> dict:
    """The measures of a designed state-feedback run (module docstring) with its design model,
    design speed, the model it ran on and ``stable``."""
    found = maneuver(case, ds)
    tf = float(found["reference"]["tf"]) if "tf" in found["reference"] else float(
        found["reference"]["time"][-1])
    t = times(ds)
    tip = variable(case, ds, "tip_transverse").values
    torque = variable(case, ds, "hub_torque").values
    stable = attr(case, ds, "integrator_status") == "success" and bool(np.all(np.isfinite(tip)))
    return {
        "case": case, "design_model": found["design"]["model"],
        "design_speed": float(found["design"]["speed"]), "model": model(case, ds), "stable": stable,
        "peak_tip_deflection_m": measures.peak(tip) if stable else math.nan,
        "residual_vibration_m": residual(case, ds) if stable else math.nan,
        "settling_time_s": measures.settling_time(t, tip, tf, SETTLING_BAND) if stable else math.nan,
        "peak_torque_Nm": measures.peak(torque) if stable else math.nan,
    }


def design_table(datasets: Mapping[str, xr.Dataset]) -> list[dict]:
    """One row per design (model, speed): the measures on its own model (``own``) and on
    :data:`REFERENCE_MODEL` (``reference``; None when not run), the relative ``gap`` of the peak
    and residual deflections and ``good`` (module docstring; None, not judged, when the design
    did not run on its own model); sorted by model and speed."""
    runs = [closed_loop_measures(case, ds) for case, ds in datasets.items() if is_designed(case, ds)]
    rows = {}
    for run in runs:
        row = rows.setdefault((run["design_model"], run["design_speed"]),
                              {"design_model": run["design_model"], "design_speed": run["design_speed"],
                               "own": None, "reference": None})
        if run["model"] == run["design_model"]:
            row["own"] = run
        if run["model"] == REFERENCE_MODEL:
            row["reference"] = run
    for row in rows.values():
        own, truth = row["own"], row["reference"]
        row["gap"] = math.nan
        if own and truth and own["stable"] and truth["stable"]:
            row["gap"] = max(abs(truth[key] - own[key]) / own[key]
                             for key in ("peak_tip_deflection_m", "residual_vibration_m"))
        # not judged (None) where the study has no run of the design on its own model: no prediction
        row["good"] = (None if truth and truth["stable"] and not own
                       else bool(truth and truth["stable"] and row["gap"] <= TRUST_TOLERANCE))
    return [rows[key] for key in sorted(rows)]


def verdicts(table: list[dict]) -> dict[str, str]:
    """Per design model, a sentence: the speeds where its controller is good enough on
    :data:`REFERENCE_MODEL`, the first speed where it is not and why, with the numbers."""
    out = {}
    for name in dict.fromkeys(row["design_model"] for row in table):
        rows = [row for row in table if row["design_model"] == name and row["reference"]]
        if not rows:
            continue
        unjudged = [row["design_speed"] for row in rows if row["good"] is None]
        rows = [row for row in rows if row["good"] is not None]
        if not rows:
            out[name] = (f"not judged: the study runs this design on {REFERENCE_MODEL} only (at "
                         f"{', '.join(f'{speed:g}' for speed in unjudged)} rad/s), not on {name} itself, whose run "
                         "is the prediction")
            continue
        failed = next((row for row in rows if not row["good"]), None)
        worst = max((row["gap"] for row in rows if row["good"]), default=math.nan)
        if failed is None:
            out[name] = (f"good enough on {REFERENCE_MODEL} at every design speed up to "
                         f"{rows[-1]['design_speed']:g} rad/s (largest gap {100 * worst:.2g} %)")
            continue
        good = [row["design_speed"] for row in rows if row["good"] and row["design_speed"] < failed["design_speed"]]
        upto = f"good enough up to {max(good):g} rad/s (largest gap {100 * worst:.2g} %); " if good else ""
        own = failed["own"]
        if not failed["reference"]["stable"]:
            why = (f"unstable on {REFERENCE_MODEL}"
                   + ("" if own is None or own["stable"] else f", and on {name} itself"))
        else:
            why = f"its {REFERENCE_MODEL} tip deflections differ by {100 * failed['gap']:.2g} % from its prediction"
        unstable = [row["design_speed"] for row in rows if not row["reference"]["stable"]]
        later = (f"; unstable on {REFERENCE_MODEL} from {min(unstable):g} rad/s"
                 if unstable and min(unstable) > failed["design_speed"] else "")
        out[name] = f"{upto}at {failed['design_speed']:g} rad/s {why}{later}"
    return out


def performance(table: list[dict]) -> dict[str, str]:
    """Per design model, a sentence on its residual vibration on :data:`REFERENCE_MODEL` against
    the other design models' at the same design speed (stable loops only): the speeds where it
    leaves the least (within :data:`TIE`) and where it does not, with its residual and the
    others' (m)."""
    out = {}
    truth = {(row["design_model"], row["design_speed"]): row["reference"]["residual_vibration_m"]
             for row in table if row["reference"] and row["reference"]["stable"]}
    for name in dict.fromkeys(row["design_model"] for row in table):
        best, beaten = [], []
        for speed in sorted(at for design, at in truth if design == name):
            others = {design: value for (design, at), value in truth.items() if at == speed and design != name}
            if not others:
                continue
            mine = truth[(name, speed)]
            compared = (f"{speed:g} rad/s ({mine:.2g} m against "
                        + ", ".join(f"{value:.2g} m ({design})" for design, value in others.items()) + ")")
            (best if mine <= (1.0 + TIE) * min(others.values()) else beaten).append(compared)
        unstable = [row["design_speed"] for row in table if row["design_model"] == name and row["reference"]
                    and not row["reference"]["stable"]]
        parts = ([f"the least residual vibration on {REFERENCE_MODEL} of the designs at " + "; ".join(best)]
                 if best else [])
        parts += ["more than another design at " + "; ".join(beaten)] if beaten else []
        if unstable:
            speeds = ", ".join(f"{speed:g}" for speed in unstable)
            parts.append(f"unstable on {REFERENCE_MODEL} at {speeds} rad/s")
        if parts:
            out[name] = "; ".join(parts)
    return out
