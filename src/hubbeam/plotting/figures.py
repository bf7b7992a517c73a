"""Drawing shared by the figure modules (which cases feed a figure: hubbeam.reporting.products).

The figure functions receive ``{case name: xarray.Dataset}`` following the simulation dataset
contract of ``docs/architecture.md``, read them through :mod:`hubbeam.results.reader` and never touch
files.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.plotting.style import mark_time, model_style
from hubbeam.reporting.formatting import number
from hubbeam.results.reader import (
    DatasetError,
    diverged_at,
    large_deflection_ratio,
    left_range_at,
    maneuver,
    model,
    n_modes,
    times,
    variable,
)


def curve_label(case: str, ds: xr.Dataset) -> str:
    """``"FOAM, n = 5"``: the model and its mode count, as every legend names them."""
    return f"{model(case, ds)}, n = {n_modes(case, ds)}"


def require_datasets(key: str, datasets: Mapping[str, xr.Dataset], what: str) -> None:
    """Fail when a figure got no dataset for ``what`` (e.g. 'a CFOAM run')."""
    if not datasets:
        raise DatasetError(f"{key}: no dataset for {what}; add a matching case to the config")


# --- drawing shared by the time-series figures --------------------------------------------------

def plot_series(ax, case: str, ds: xr.Dataset, name: str, *, label: str | None = None,
                variant: int = 0, scale: float = 1.0, mode: int | None = None, **style):
    """Draw ``name`` (or its ``mode`` column) of ``case`` against time in the model's style.

    A diverged run, or one stopped outside the range of the models, is drawn up to its stop (its
    data are NaN after it) and marked; a run beyond the small-deflection limit is named so in the
    legend (:mod:`hubbeam.model.validity`).
    """
    da = variable(case, ds, name)
    if mode is not None:
        da = da.sel(mode=mode)
    props = model_style(model(case, ds), variant) | style
    line, = ax.plot(times(ds), scale * da.values, label=label or curve_label(case, ds), **props)
    t_div = diverged_at(case, ds)
    if t_div is not None:
        mark_time(ax, t_div, f"{model(case, ds)} diverged at t = {t_div:.2f} s", color=props["color"])
        line.set_label(f"{line.get_label()} (diverged)")
    t_left = left_range_at(case, ds)
    if t_left is not None:
        mark_time(ax, t_left, f"{model(case, ds)} left the models' range at t = {t_left:.2f} s",
                  color=props["color"])
        line.set_label(f"{line.get_label()} (left range)")
    ratio = large_deflection_ratio(case, ds)
    if ratio is not None:
        line.set_label(f"{line.get_label()} (large deflection, max |v(L)| = {ratio:.2g} L)")
    return line


def mark_maneuver_end(ax, case: str, ds: xr.Dataset) -> None:
    """Mark ``t_f``, the end of the spin-up or torque pulse (start of the residual vibration)."""
    tf = maneuver(case, ds).get("tf")
    if tf is not None:
        mark_time(ax, float(tf), f"$t_f$ = {number(float(tf), 6)} s")


def limit_to_bounded(ax, datasets: Mapping[str, xr.Dataset], name: str) -> None:
    """Keep bounded runs readable next to runs stopped early (diverged or left the range).

    When the axes hold both stopped and completed runs, the y-range is the range of the
    completed runs widened by that range on either side; the stopped curve leaves the frame and
    its stop is marked by :func:`plot_series`.
    """
    bounded = [variable(c, ds, name).values for c, ds in datasets.items()
               if diverged_at(c, ds) is None and left_range_at(c, ds) is None]
    if len(bounded) == len(datasets) or not bounded:
        return
    low = min(float(np.nanmin(values)) for values in bounded)
    high = max(float(np.nanmax(values)) for values in bounded)
    if high > low:
        ax.set_ylim(low - (high - low), high + (high - low))
