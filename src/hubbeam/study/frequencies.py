"""The natural frequencies of each case of a study: its beam, tip mass or body, transverse functions
and root, with the hub held and at rest, from the case's system matrices.

The study's eigen-analysis grids (``eigen``) take tip masses as point masses over mass and position;
these are the case's own, so a payload with rotary inertia or a compliant root shows here as it runs
(``hubbeam.model.eigen.natural_frequencies``: the generalised eigenproblem of ``K2`` and the
transverse mass with the body's rotary inertia, the root's angle joining ``q2`` on a spring).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import xarray as xr

from hubbeam.model.eigen import natural_frequencies
from hubbeam.model.matrices import from_dataset
from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import number

#: how many frequencies the report lists per case
COUNT = 3


def case_frequencies(name: str, case, matrices: xr.Dataset, count: int = COUNT) -> dict:
    """The row of case ``name`` (a ``Case``: its modes, tip mass and root spring) from its matrices
    dataset ``matrices`` (possibly of more modes): ``frequencies_hz``, its first ``count`` natural
    frequencies (Hz, hub held, at rest), with what sets them."""
    sm = from_dataset(matrices, case.modes)
    found = natural_frequencies(sm, case.root_spring) / (2.0 * math.pi)
    tip = case.tip_mass
    return {"case": name, "modes": case.modes, "tip_mass_kg": tip.mass, "tip_inertia_kg_m2": tip.inertia,
            "functions": case.transverse_functions, "root_spring": case.root_spring is not None,
            "frequencies_hz": [float(f) for f in found[:count]]}


def frequencies_markdown(rows: Sequence[Mapping]) -> str:
    """A line per case: its modes, tip mass and rotary inertia, functions, root and frequencies."""
    count = max((len(row["frequencies_hz"]) for row in rows), default=0)

    def cells(row):
        found = [number(f, 6) for f in row["frequencies_hz"]]
        return [row["case"], row["modes"], number(row["tip_mass_kg"]), number(row["tip_inertia_kg_m2"]),
                row["functions"].replace("_", "-"), "spring" if row["root_spring"] else "clamped",
                *found, *([""] * (count - len(found)))]

    return markdown_table(("case", "modes", "tip mass (kg)", "rotary inertia (kg m2)", "functions", "root",
                           *(f"f{k + 1} (Hz)" for k in range(count))), (cells(row) for row in rows))
