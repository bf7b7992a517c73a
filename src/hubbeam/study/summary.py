"""One row of the study report per simulation: the measures of the tip deflection v(L).

Every measure reads the simulation dataset only (variables and attributes of
``hubbeam.simulate.build_dataset``): the peak ``max |v(L)|`` and its time, the residual amplitude
``max |v(L)|`` after the maneuver ends, its validity (:mod:`hubbeam.validity`: beyond the
small-deflection range, left the range of the models, diverged), and the result of the optional
convergence check (``numerics.convergence_check``).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam import measures, validity

#: columns of a summary row, in the order of the report's table and csv file
COLUMNS = ("case", "model", "maneuver", "modes", "tip_mass_kg", "peak_tip_deflection_m",
           "peak_time_s", "maneuver_end_s", "residual_amplitude_m", "validity", "max_deflection_ratio",
           "diverged", "diverged_at_s",
           "convergence", "convergence_tolerance_diff_m", "convergence_modes_diff_m")


def maneuver_end(maneuver: Mapping) -> float:
    """When the hub input stops changing, s: ``tf`` of the spin-up (Eq. 43), of the torque pulse
    (Eq. 44) or of a pd maneuver's reference spin-up; the last time of a table otherwise."""
    if "tf" in maneuver:
        return float(maneuver["tf"])
    if "time" in maneuver:
        return float(maneuver["time"][-1])
    if "reference" in maneuver:
        return maneuver_end(maneuver["reference"])
    raise ValueError(f"maneuver {dict(maneuver)} has neither tf, a time table nor a reference")


def dataset_maneuver(ds: xr.Dataset) -> dict:
    """The resolved maneuver a simulation dataset records (attribute ``maneuver``, JSON)."""
    raw = ds.attrs["maneuver"]
    return json.loads(raw) if isinstance(raw, str) else dict(raw)


def convergence_result(attrs: Mapping) -> str:
    """``not checked``, ``converged`` or ``NOT converged`` from a dataset's attributes."""
    if "convergence_check" not in attrs:
        return "not checked"
    return "NOT converged" if "not converged" in str(attrs.get("warnings", "")) else "converged"


def case_summary(case: str, ds: xr.Dataset) -> dict:
    """The summary row of ``case``'s simulation dataset ``ds`` (keys :data:`COLUMNS`)."""
    attrs = ds.attrs
    maneuver = dataset_maneuver(ds)
    t = ds["time"].values
    tip = ds["tip_transverse"].values
    bounded = bool(np.isfinite(tip).any())
    end = maneuver_end(maneuver)
    diverged = int(attrs["diverged"]) == 1
    return {
        "case": case,
        "model": str(attrs["model"]),
        "maneuver": maneuver["kind"],
        "modes": int(attrs["n_modes"]),
        "tip_mass_kg": float(attrs["tip_mass_kg"]),
        "peak_tip_deflection_m": measures.peak(tip) if bounded else math.nan,
        "peak_time_s": measures.peak_time(t, tip) if bounded else math.nan,
        "maneuver_end_s": end,
        "residual_amplitude_m": measures.residual_amplitude(t, tip, end),
        "validity": validity.describe(attrs),
        "max_deflection_ratio": float(attrs["max_deflection_ratio"]),
        "diverged": diverged,
        "diverged_at_s": float(attrs["diverged_at_s"]) if diverged else math.nan,
        "convergence": convergence_result(attrs),
        "convergence_tolerance_diff_m": float(attrs.get("convergence_tolerance_diff_m", math.nan)),
        "convergence_modes_diff_m": float(attrs.get("convergence_modes_diff_m", math.nan)),
    }
