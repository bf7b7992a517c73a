"""Robustness maps of sampled controllers (:mod:`hubbeam.control.robustness`): spectral radius against each parameter.

One panel per moved plant parameter, one line per case (its controller built for the nominal
plant), its nominal value as a dot; the unit circle's radius 1 as a horizontal line (above it the
loop is unstable).
"""

from __future__ import annotations

import math
import textwrap

import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure


def plot(robustness: xr.Dataset):
    """Spectral radius against each parameter per case (module docstring)."""
    parameters = [name.removeprefix("radius_") for name in robustness.data_vars if name.startswith("radius_")]
    columns = min(3, len(parameters))
    rows = math.ceil(len(parameters) / columns)
    fig, axes = new_figure(rows, columns, height=3.0 * rows, width=8.0, sharex=False)
    flat = axes.ravel()
    for ax, name in zip(flat, parameters):
        grid = robustness[f"{name}_value"]
        for k, case in enumerate(robustness["case"].values):
            color = SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)]
            ax.plot(grid.values, robustness[f"radius_{name}"].sel(case=case).values, color=color, label=str(case))
            ax.plot(float(robustness[f"nominal_{name}"].sel(case=case)),
                    float(robustness["nominal_radius"].sel(case=case)), "o", color=color, markersize=4)
        ax.axhline(1.0, color="0.3", linewidth=0.8)
        ax.set_xlabel(axis_label(name.replace("_", " "), grid.attrs.get("units", "1")))
        ax.set_ylabel(axis_label(r"$\max|z|$", "1"))
        ax.set_title(textwrap.fill(grid.attrs.get("long_name", name), 34), fontsize=7)
    for ax in flat[len(parameters):]:
        ax.set_visible(False)
    flat[0].legend(loc="best", fontsize=6)
    return fig
