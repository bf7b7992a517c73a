"""A comparison figure of a study: several simulations overlaid (``study.comparisons``).

Panels: the tip deflection v(L) = f2(L) q2, the hub angular velocity and the hub torque of every
case named in the comparison, one colour per case and the model's dash pattern; a diverged run
is drawn up to its divergence and says so in the legend, and the axes keep the bounded runs
readable (``hubbeam.plotting.figures.limit_to_bounded``).
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.model import validity
from hubbeam.plotting.case_figure import SERIES
from hubbeam.plotting.figures import limit_to_bounded
from hubbeam.plotting.style import (
    MODEL_STYLE,
    SEQUENCE_COLORS,
    axis_label,
    new_figure,
    panel_title,
)
from hubbeam.results.reader import attr, model, n_modes, times, variable


def plot(name: str, datasets: Mapping[str, xr.Dataset]):
    """Overlay the simulations ``{case: dataset}`` of comparison ``name``."""
    fig, axes = new_figure(3, 1, height=6.0)
    axes = axes[:, 0]
    for k, (case, ds) in enumerate(datasets.items()):
        model_name = model(case, ds)
        label = f"{case} ({model_name}, n = {n_modes(case, ds)})"
        if attr(case, ds, "validity") != "valid":
            label += f", {validity.describe(ds.attrs)}"
        props = {"color": SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)],
                 "linestyle": MODEL_STYLE.get(model_name, {}).get("linestyle", "-")}
        for index, (series, ylabel) in enumerate(SERIES.values()):
            axes[index].plot(times(ds), variable(case, ds, series).values,
                             label=label if index == 0 else None, **props)
            axes[index].set_ylabel(ylabel)
    for ax, (series, _) in zip(axes, SERIES.values()):
        limit_to_bounded(ax, datasets, series)
    axes[-1].set_xlabel(axis_label("time $t$", "s"))
    panel_title(axes[0], 0, f"comparison {name}")
    axes[0].legend(loc="best", fontsize=7)
    return fig
