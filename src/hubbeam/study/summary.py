"""One row of the study report per simulation: the measures of the tip deflection v(L).

Every measure reads the simulation dataset through :mod:`hubbeam.results.reader`: the peak
``max |v(L)|`` and its time, the residual amplitude ``max |v(L)|`` after the command ends (the
maneuver's end, delayed by the duration of a command shaper, ``hubbeam.model.shapers``), the
shaper and its move-time penalty (that duration: the shaped command ends so much later), its
validity (:mod:`hubbeam.model.validity`: beyond the small-deflection range, left the range of the
models, diverged), and the result of the optional convergence check
(``numerics.convergence_check``).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from hubbeam.model import validity
from hubbeam.results import measures
from hubbeam.results.reader import (
    attr,
    convergence_result,
    diverged_at,
    maneuver,
    maneuver_end,
    model,
    n_modes,
    shaper,
    shaper_duration,
    times,
    tip_mass,
    variable,
)

#: columns of a summary row, in the order of the report's table and csv file
COLUMNS = ("case", "model", "maneuver", "modes", "tip_mass_kg", "peak_tip_deflection_m",
           "peak_time_s", "maneuver_end_s", "shaper", "move_time_penalty_s", "residual_amplitude_m", "validity",
           "max_deflection_ratio",
           "diverged", "diverged_at_s",
           "convergence", "convergence_tolerance_diff_m", "convergence_modes_diff_m")


#: the ``shaper`` of an unshaped run's row
NO_SHAPER = "none"


def residual(case: str, ds: xr.Dataset) -> float:
    """The residual amplitude of ``case``'s run: ``max |v(L)|`` after its command ends, the
    maneuver's end (a reference's last time) delayed by a shaper's duration; the one definition of
    the residual every section of the study report uses (NaN where nothing finite is left)."""
    tip = variable(case, ds, "tip_transverse").values
    return measures.shaped_residual_amplitude(times(ds), tip, maneuver_end(maneuver(case, ds)),
                                              shaper_duration(case, ds))


def case_summary(case: str, ds: xr.Dataset) -> dict:
    """The summary row of ``case``'s simulation dataset ``ds`` (keys :data:`COLUMNS`)."""
    found = maneuver(case, ds)
    t = times(ds)
    tip = variable(case, ds, "tip_transverse").values
    bounded = bool(np.isfinite(tip).any())
    end = maneuver_end(found)
    shaped = shaper(case, ds)
    penalty = shaper_duration(case, ds)
    stopped = diverged_at(case, ds)
    return {
        "case": case,
        "model": model(case, ds),
        "maneuver": found["kind"],
        "modes": n_modes(case, ds),
        "tip_mass_kg": tip_mass(case, ds),
        "peak_tip_deflection_m": measures.peak(tip) if bounded else math.nan,
        "peak_time_s": measures.peak_time(t, tip) if bounded else math.nan,
        "maneuver_end_s": end,
        "shaper": NO_SHAPER if shaped is None else shaped["name"],
        "move_time_penalty_s": penalty,
        "residual_amplitude_m": residual(case, ds),
        "validity": validity.describe(ds.attrs),
        "max_deflection_ratio": float(attr(case, ds, "max_deflection_ratio")),
        "diverged": stopped is not None,
        "diverged_at_s": math.nan if stopped is None else float(attr(case, ds, "diverged_at_s")),
        "convergence": convergence_result(ds.attrs),
        "convergence_tolerance_diff_m": float(ds.attrs.get("convergence_tolerance_diff_m", math.nan)),
        "convergence_modes_diff_m": float(ds.attrs.get("convergence_modes_diff_m", math.nan)),
    }
