"""The dataset helpers shared by the figure modules (which cases feed a figure: hubbeam.products).

The figure functions receive ``{case name: xarray.Dataset}`` following the simulation dataset
contract of ``docs/architecture.md`` and never touch files.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.plotting.style import mark_time, model_style


class FigureDataError(ValueError):
    """A dataset handed to a figure lacks what the figure needs (names case and item)."""


# --- dataset metadata ---------------------------------------------------------------------------

def attr(case: str, ds: xr.Dataset, key: str):
    """Global attribute ``key`` of ``case``'s dataset, or a FigureDataError naming both."""
    try:
        return ds.attrs[key]
    except KeyError:
        raise FigureDataError(f"dataset of case {case!r} has no attribute {key!r}") from None


def variable(case: str, ds: xr.Dataset, name: str) -> xr.DataArray:
    """Variable ``name`` of ``case``'s dataset, or a FigureDataError naming both."""
    if name not in ds.data_vars:
        raise FigureDataError(
            f"dataset of case {case!r} has no variable {name!r} (has: {', '.join(sorted(ds.data_vars))})")
    return ds[name]


def model(case: str, ds: xr.Dataset) -> str:
    return str(attr(case, ds, "model"))


def maneuver(case: str, ds: xr.Dataset) -> dict:
    """The ``maneuver`` attribute (JSON) as a dict, e.g. ``{"kind": "prescribed", "wf": 3.0, ...}``."""
    raw = attr(case, ds, "maneuver")
    try:
        return json.loads(raw) if isinstance(raw, str) else dict(raw)
    except (TypeError, ValueError) as err:
        raise FigureDataError(f"case {case!r}: attribute 'maneuver' is not JSON: {raw!r}") from err


def maneuver_value(case: str, ds: xr.Dataset, key: str) -> float:
    """One number of the maneuver (``wf``, ``tf``, ``tau_max``), with a clear error if absent."""
    value = maneuver(case, ds).get(key)
    if value is None:
        raise FigureDataError(f"case {case!r}: maneuver has no {key!r} ({maneuver(case, ds)})")
    return float(value)


def n_modes(case: str, ds: xr.Dataset) -> int:
    return int(attr(case, ds, "n_modes"))


def tip_mass(case: str, ds: xr.Dataset) -> float:
    return float(attr(case, ds, "tip_mass_kg"))


def tip_position(case: str, ds: xr.Dataset) -> float:
    return float(attr(case, ds, "tip_position_m"))


def diverged_at(case: str, ds: xr.Dataset) -> float | None:
    """Time (s) at which the run diverged, or None when it did not."""
    if int(attr(case, ds, "diverged")) != 1:
        return None
    t = float(ds.attrs.get("diverged_at_s", math.nan))
    if math.isnan(t):  # flag set but no time recorded: last finite sample of the run
        finite = np.isfinite(variable(case, ds, "tip_transverse").values)
        t = float(ds["time"].values[finite][-1]) if finite.any() else float(ds["time"].values[0])
    return t


def left_range_at(case: str, ds: xr.Dataset) -> float | None:
    """Time (s) at which the run was stopped outside the range of the models with a bounded
    response (:mod:`hubbeam.validity`), or None when it was not."""
    return float(attr(case, ds, "stopped_at_s")) if int(attr(case, ds, "left_range")) == 1 else None


def large_deflection(case: str, ds: xr.Dataset) -> str | None:
    """``"max |v(L)| = 0.53 L"`` for a completed run beyond the small-deflection limit of the
    models (``validity = large_deflection``), None otherwise."""
    if attr(case, ds, "validity") != "large_deflection":
        return None
    return f"max |v(L)| = {float(attr(case, ds, 'max_deflection_ratio')):.2g} L"


def curve_label(case: str, ds: xr.Dataset) -> str:
    """``"FOAM, n = 5"``: the model and its mode count, as every legend names them."""
    return f"{model(case, ds)}, n = {n_modes(case, ds)}"


def select(datasets: Mapping[str, xr.Dataset], **criteria) -> dict[str, xr.Dataset]:
    """The datasets whose model / maneuver numbers / tip mass equal ``criteria``.

    Keys: ``model``, ``kind``, ``wf``, ``tau_max``, ``tf``, ``tip_mass``, ``n_modes``.
    """
    def value(case, ds, key):
        if key == "model":
            return model(case, ds)
        if key == "n_modes":
            return n_modes(case, ds)
        if key == "tip_mass":
            return tip_mass(case, ds)
        return maneuver(case, ds).get(key)

    def matches(case, ds):
        for key, wanted in criteria.items():
            got = value(case, ds, key)
            if isinstance(wanted, float) or isinstance(got, float):
                if got is None or not math.isclose(float(got), float(wanted), rel_tol=1e-9, abs_tol=1e-12):
                    return False
            elif got != wanted:
                return False
        return True

    return {case: ds for case, ds in datasets.items() if matches(case, ds)}


def distinct(datasets: Mapping[str, xr.Dataset], key: str) -> list[float]:
    """Sorted distinct values of a maneuver number (``wf``, ``tau_max``) or ``tip_mass``."""
    if key == "tip_mass":
        values = {tip_mass(c, ds) for c, ds in datasets.items()}
    else:
        values = {maneuver_value(c, ds, key) for c, ds in datasets.items()}
    return sorted(values)


def require_datasets(key: str, datasets: Mapping[str, xr.Dataset], what: str) -> None:
    """Fail when a figure got no dataset for ``what`` (e.g. 'a CFOAM run')."""
    if not datasets:
        raise FigureDataError(f"{key}: no dataset for {what}; add a matching case to the config")


def format_number(x: float) -> str:
    """Short number for titles and legends: 2.8, 0.1, 400 (no trailing zeros)."""
    return f"{x:g}"


# --- drawing shared by the time-series figures --------------------------------------------------

def plot_series(ax, case: str, ds: xr.Dataset, name: str, *, label: str | None = None,
                variant: int = 0, scale: float = 1.0, mode: int | None = None, **style):
    """Draw ``name`` (or its ``mode`` column) of ``case`` against time in the model's style.

    A diverged run, or one stopped outside the range of the models, is drawn up to its stop (its
    data are NaN after it) and marked; a run beyond the small-deflection limit is named so in the
    legend (:mod:`hubbeam.validity`).
    """
    da = variable(case, ds, name)
    if mode is not None:
        da = da.sel(mode=mode)
    props = model_style(model(case, ds), variant) | style
    line, = ax.plot(ds["time"].values, scale * da.values, label=label or curve_label(case, ds), **props)
    t_div = diverged_at(case, ds)
    if t_div is not None:
        mark_time(ax, t_div, f"{model(case, ds)} diverged at t = {t_div:.2f} s", color=props["color"])
        line.set_label(f"{line.get_label()} (diverged)")
    t_left = left_range_at(case, ds)
    if t_left is not None:
        mark_time(ax, t_left, f"{model(case, ds)} left the models' range at t = {t_left:.2f} s",
                  color=props["color"])
        line.set_label(f"{line.get_label()} (left range)")
    large = large_deflection(case, ds)
    if large is not None:
        line.set_label(f"{line.get_label()} (large deflection, {large})")
    return line


def mark_maneuver_end(ax, case: str, ds: xr.Dataset) -> None:
    """Mark ``t_f``, the end of the spin-up or torque pulse (start of the residual vibration)."""
    tf = maneuver(case, ds).get("tf")
    if tf is not None:
        mark_time(ax, float(tf), f"$t_f$ = {format_number(float(tf))} s")


def limit_to_bounded(ax, datasets: Mapping[str, xr.Dataset], name: str) -> None:
    """Keep bounded runs readable next to runs stopped early (diverged or left the range).

    When the axes hold both stopped and completed runs, the y-range is the range of the
    completed runs widened by that range on either side; the stopped curve leaves the frame and
    its stop is marked by :func:`plot_series`.
    """
    bounded = [ds[name].values for c, ds in datasets.items()
               if diverged_at(c, ds) is None and left_range_at(c, ds) is None]
    if len(bounded) == len(datasets) or not bounded:
        return
    low = min(float(np.nanmin(values)) for values in bounded)
    high = max(float(np.nanmax(values)) for values in bounded)
    if high > low:
        ax.set_ylim(low - (high - low), high + (high - low))
