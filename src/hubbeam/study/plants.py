"""The study report's table of plants: what each plant holds, which cases run it, its natural
frequencies (hub held, at rest) with how far they are converged, its free hub's first flexible
frequency and the critical speed of each model, read from the plant's dataset
(``plants/<plant>/plant.nc``, :mod:`hubbeam.linear.plant_dataset`)."""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import number

#: natural frequencies listed per plant
COUNT = 3


def plant_row(ds: xr.Dataset) -> dict:
    """The row of one plant's dataset: its name, cases, what it holds, its first :data:`COUNT`
    frequencies with their convergence, its free hub's first flexible frequency, its critical speeds."""
    holds = json.loads(ds.attrs["plant_config"])
    held = ds["held_frequency"].values[:COUNT]
    free = ds["free_frequency"].values
    return {"plant": ds.attrs["plant"], "cases": json.loads(ds.attrs["cases"]), "holds": holds,
            "held_hz": [float(f) for f in held], "converged": [bool(c) for c in ds["converged"].values[:COUNT]],
            "relative_change": [float(c) for c in ds["relative_change"].values[:COUNT]],
            "more_modes": int(ds.attrs["more_modes"]),
            "free_hz": float(free[0]) if free.size else float("nan"),
            "critical_speed": {str(model): float(speed)
                               for model, speed in zip(ds["model"].values, ds["critical_speed"].values)}}


def _holds(holds: Mapping) -> str:
    """What a plant holds, in a few words."""
    parts = [f"{holds['modes']} {holds['transverse_functions'].replace('_', '-')} modes"]
    if holds["tip_mass_kg"] > 0.0:
        body = f"{number(holds['tip_mass_kg'])} kg at {number(holds['tip_position_m'])} m"
        if holds["tip_inertia_kg_m2"] or holds["tip_offset_m"]:
            body += f" (J {number(holds['tip_inertia_kg_m2'])} kg m2, offset {number(holds['tip_offset_m'])} m)"
        parts.append(body)
    if holds["root_spring"]:
        parts.append(f"root spring {number(holds['root_spring']['stiffness'])} N m/rad")
    if holds["drive"]:
        parts.append("drive")
    if holds["damping"]:
        parts.append(f"{holds['damping']['kind']} damping")
    return ", ".join(parts)


def plants_markdown(rows: Sequence[Mapping]) -> str:
    """A line per plant (:func:`plant_row`): a frequency not converged with more assumed functions
    is marked with its relative change."""
    def frequency(row, k):
        if k >= len(row["held_hz"]):
            return ""
        text = number(row["held_hz"][k], 6)
        change = number(100 * row["relative_change"][k], 2)
        return text if row["converged"][k] else f"{text} (not converged: {change} %)"

    models = list(rows[0]["critical_speed"]) if rows else []
    return markdown_table(
        ("plant", "cases", "holds", *(f"f{k + 1} held (Hz)" for k in range(COUNT)), "f1 free (Hz)",
         *(f"{model} critical (rad/s)" for model in models)),
        ([row["plant"], ", ".join(row["cases"]), _holds(row["holds"]), *(frequency(row, k) for k in range(COUNT)),
          number(row["free_hz"], 6),
          *(number(row["critical_speed"][model]) if np.isfinite(row["critical_speed"][model]) else "none"
            for model in models)] for row in rows))
