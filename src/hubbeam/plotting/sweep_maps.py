"""Beyond the paper: maps of the peak tip deflection from the parameter sweeps (hubbeam.simulation.sweep).

``plot(sweep)`` draws the figure the sweep's configuration asks for (``figure.kind`` in the
``sweep_config`` attribute), from the sweep dataset only:

* ``peak``: one panel per model, the peak transverse tip deflection over the two swept
  parameters (logarithmic colour scale), the runs each validity category of
  :mod:`hubbeam.model.validity` flags hatched (diverged, left the models' range, large deflection);
* ``departure``: (a) the relative difference ``|peak_model - peak_reference| / peak_reference``
  with the ``threshold`` contour, runs where ``model`` stopped early hatched (they depart by
  definition), (b) the reference model's peak with the same contour.

A map of three axes shows the first two in one panel per value of the third, ``figure.slices``
of them evenly spread over its grid (one row per model for ``peak``; the relative difference with
the ``threshold`` contour for ``departure``), all on one colour scale.

Where ``wf`` is swept, TLAM's critical speed (``critical_speed`` of the dataset, from
:func:`hubbeam.model.eigen.critical_speed_sweep`) is drawn: a line at ``wf = Omega_c``, or the curve
``Omega_c(m_t)`` / ``Omega_c(l)`` when the tip mass or its position is the other axis.
"""

from __future__ import annotations

import json
import math

import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm
from matplotlib.patches import Patch
from matplotlib.ticker import NullFormatter

from hubbeam.model import validity
from hubbeam.plotting.style import axis_label, new_figure, panel_title
from hubbeam.results.reader import DatasetError

PEAK = "peak_tip_deflection"
DIVERGED_COLOR = "0.8"
#: hatch and legend text of the cells of each flagged validity category (hubbeam.model.validity)
MARKS = {
    "diverged": ("////", "diverged (beyond the critical speed)"),
    "left_range": ("\\\\", "left the model's range ($|v(L)| >$ limit)"),
    "large_deflection": ("..", "large deflection ($|v(L)| >$ small-deflection limit)"),
}
CRITICAL_COLOR = "#E69F00"
DEPARTURE_COLOR = "cyan"
#: axis labels of the swept parameters
AXIS_LABELS = {"wf": "Final hub speed $\\omega_f$", "tf": "Maneuver time $t_f$",
               "tau_max": "Torque amplitude $\\tau_m$", "tip_mass": "Tip mass $m_t$",
               "tip_position": "Tip-mass position $l$"}


def plot(sweep: xr.Dataset):
    """The figure of the sweep dataset ``sweep`` (see the module docstring)."""
    for name in (PEAK, "validity", "critical_speed"):
        if name not in sweep.variables:
            raise DatasetError(f"sweep dataset has no variable {name!r} "
                                  f"(has: {', '.join(sorted(sweep.variables))})")
    config = json.loads(sweep.attrs["sweep_config"])
    figure = config["figure"]
    if len(config["axes"]) == 3:
        return _slices(sweep, config)
    if figure["kind"] == "peak":
        return _peak_maps(sweep, config)
    return _departure_map(sweep, config, figure["model"], figure["reference"],
                          float(figure["threshold"]))


def _axes_of(sweep: xr.Dataset, config: dict):
    x_name, y_name = config["axes"][:2]
    return x_name, y_name, sweep[x_name], sweep[y_name]


def _label(coord: xr.DataArray) -> str:
    return axis_label(AXIS_LABELS.get(coord.name, coord.name), coord.attrs.get("units", ""))


def _field(values: xr.DataArray) -> np.ndarray:
    """(axis 1, axis 2) values as the (rows = axis 2, columns = axis 1) array pcolormesh wants."""
    return np.asarray(values.values, dtype=float).T


def _cell_edges(values: np.ndarray) -> np.ndarray:
    """The grid values with one more half cell on each side (for region outlines on cell edges)."""
    first = values[0] - 0.5 * (values[1] - values[0])
    last = values[-1] + 0.5 * (values[-1] - values[-2])
    return np.concatenate([[first], values, [last]])


def _hatch_flagged(ax, x, y, codes: xr.DataArray) -> list[str]:
    """Hatch the cells of every flagged validity category (:data:`MARKS`; a stopped run's peak
    is NaN, so the grey axes background shows there); the categories found.

    Each region is a filled contour at level 0.5 of its 0/1 mask padded by half a cell on each
    side, so that its outline runs along the cell edges of the map.
    """
    found = []
    for name, (hatch, _) in MARKS.items():
        mask = _field(codes == validity.CATEGORIES.index(name))
        if not mask.any():
            continue
        padded = np.pad(mask.astype(float), 1, mode="edge")
        ax.contourf(_cell_edges(np.asarray(x)), _cell_edges(np.asarray(y)), padded,
                    levels=[0.5, 1.5], colors="none", hatches=[hatch])
        found.append(name)
    return found


def log_ticks(vmin: float, vmax: float, most: int = 7) -> list[float]:
    """Ticks 1, 2, 5 x 10^k within ``[vmin, vmax]``, or only the decades if that gives more
    than ``most``."""
    decades = range(math.floor(math.log10(vmin)), math.ceil(math.log10(vmax)) + 1)
    ticks = [m * 10.0**k for k in decades for m in (1, 2, 5) if vmin <= m * 10.0**k <= vmax]
    if len(ticks) > most:
        ticks = [10.0**k for k in decades if vmin <= 10.0**k <= vmax]
    return ticks


def _colorbar(fig, mesh, ax, label: str, **kwargs) -> None:
    """Colour bar of a logarithmic map, labelled at :func:`log_ticks` in plain numbers."""
    bar = fig.colorbar(mesh, ax=ax, label=label, **kwargs)
    ticks = log_ticks(mesh.norm.vmin, mesh.norm.vmax)
    bar.set_ticks(ticks, labels=[f"{tick:g}" for tick in ticks])
    bar.ax.xaxis.set_minor_formatter(NullFormatter())
    bar.ax.yaxis.set_minor_formatter(NullFormatter())


def _critical_speed(ax, sweep: xr.Dataset, x_name: str, y_name: str) -> bool:
    """Draw TLAM's critical speed where ``wf`` is an axis; True if a line was drawn."""
    if "wf" not in (x_name, y_name):
        return False
    critical = sweep["critical_speed"].sel(eigen_model="TLAM")
    other = y_name if x_name == "wf" else x_name
    style = {"color": CRITICAL_COLOR, "linestyle": "--", "linewidth": 1.5}
    if other in critical.dims:
        speeds, along = critical.values, sweep[other].values
        xy = (speeds, along) if x_name == "wf" else (along, speeds)
        ax.plot(*xy, **style)
    else:
        speed = float(critical)
        if not np.isfinite(speed):
            return False
        (ax.axvline if x_name == "wf" else ax.axhline)(speed, **style)
    return True


def _legend(ax, flagged: list[str], critical: bool, extra=(), below=None) -> None:
    """The legend of a map panel: inside ``ax``, or under the whole figure ``below`` (a grid of
    panels, where it would hide part of the first one)."""
    handles = list(extra)
    for name in flagged:
        hatch, label = MARKS[name]
        handles.append(Patch(facecolor=DIVERGED_COLOR if name != "large_deflection" else "none",
                             hatch=hatch, edgecolor="0.3", label=label))
    if critical:
        handles.append(ax.plot([], [], color=CRITICAL_COLOR, linestyle="--", linewidth=1.5,
                               label="TLAM critical speed $\\Omega_c$")[0])
    if handles and below is not None:
        below.legend(handles=handles, loc="outside lower center", ncol=min(len(handles), 3),
                     fontsize=7, frameon=False)
    elif handles:
        ax.legend(handles=handles, loc="upper right", fontsize=7, frameon=True, framealpha=0.85)


def _peak_norm(values: np.ndarray) -> LogNorm:
    finite = values[np.isfinite(values) & (values > 0)]
    if finite.size == 0:
        raise DatasetError("sweep dataset has no finite positive peak tip deflection to map")
    return LogNorm(vmin=float(finite.min()), vmax=float(finite.max()))


def _peak_maps(sweep: xr.Dataset, config: dict):
    x_name, y_name, x, y = _axes_of(sweep, config)
    models = list(sweep["model"].values)
    fig, axes = new_figure(1, len(models), width=3.5 * len(models) + 0.8, height=3.5,
                           sharex=True, sharey=True)
    norm = _peak_norm(sweep[PEAK].values)
    mesh = None
    for k, model in enumerate(models):
        ax = axes[0, k]
        ax.set_facecolor(DIVERGED_COLOR)
        mesh = ax.pcolormesh(x, y, _field(sweep[PEAK].sel(model=model)), norm=norm,
                             cmap="viridis", shading="nearest", rasterized=True)
        codes = sweep["validity"].sel(model=model)
        flagged = _hatch_flagged(ax, x, y, codes)
        critical = _critical_speed(ax, sweep, x_name, y_name)
        _legend(ax, flagged, critical)
        counts = ", ".join(f"{int((codes == validity.CATEGORIES.index(name)).sum())} {name.replace('_', ' ')}"
                           for name in ("diverged", "left_range") if name in flagged)
        panel_title(ax, k, f"{model} ({sweep[x_name].size * sweep[y_name].size} runs"
                           + (f"; {counts}" if counts else "") + ")")
        ax.set_xlabel(_label(x))
        if k == 0:
            ax.set_ylabel(_label(y))
        ax.grid(False)
    _colorbar(fig, mesh, axes[0, :].tolist(),
              axis_label("Peak $|v(L)|$", sweep[PEAK].attrs.get("units", "m")))
    return fig


def relative_departure(sweep: xr.Dataset, model: str, reference: str) -> xr.DataArray:
    """``|peak_model - peak_reference| / peak_reference`` over the grid; ``inf`` where ``model``
    stopped early (diverged or left the range of the models) and ``reference`` did not, NaN where
    ``reference`` stopped."""
    peak = sweep[PEAK]
    difference = abs(peak.sel(model=model) - peak.sel(model=reference)) / peak.sel(model=reference)
    model_stopped = sweep["validity"].sel(model=model) >= validity.LEFT_RANGE
    reference_ok = sweep["validity"].sel(model=reference) < validity.LEFT_RANGE
    return xr.where(model_stopped & reference_ok, np.inf, difference).where(reference_ok)


def _departure_map(sweep: xr.Dataset, config: dict, model: str, reference: str,
                   threshold: float):
    x_name, y_name, x, y = _axes_of(sweep, config)
    departure = relative_departure(sweep, model, reference)
    fig, axes = new_figure(1, 2, width=7.2, height=4.4, sharex=True, sharey=True)
    ax = axes[0, 0]
    ax.set_facecolor(DIVERGED_COLOR)
    finite = departure.values[np.isfinite(departure.values) & (departure.values > 0)]
    if finite.size == 0:
        raise DatasetError(f"sweep dataset: no grid point where both {model} and {reference} "
                              "completed with different peaks; nothing to map")
    norm = LogNorm(vmin=max(float(finite.min()), 1e-4),
                   vmax=max(float(finite.max()), 10 * threshold))
    mesh = ax.pcolormesh(x, y, _field(departure.where(np.isfinite(departure))), norm=norm,
                         cmap="magma", shading="nearest", rasterized=True)
    _colorbar(fig, mesh, ax, f"|{model} - {reference}| / {reference} of the peak $|v(L)|$",
              location="bottom", shrink=0.9)
    departs = _field((departure > threshold) | np.isinf(departure))
    share = float(np.nanmean(departs))
    contour_style = {"levels": [0.5], "colors": DEPARTURE_COLOR, "linewidths": 1.3}
    for axis in axes[0]:
        axis.contour(x, y, departs.astype(float), **contour_style)
    flagged = _hatch_flagged(ax, x, y, sweep["validity"].sel(model=model))
    critical = _critical_speed(ax, sweep, x_name, y_name)
    boundary = ax.plot([], [], color=DEPARTURE_COLOR,
                       label=f"{model} departs by {threshold:.0%}")[0]
    _legend(ax, flagged, critical, extra=[boundary])
    panel_title(ax, 0, f"{model} vs {reference}: > {threshold:.0%} apart on {share:.0%} of the map")
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label(y))
    ax.grid(False)

    ax = axes[0, 1]
    ax.set_facecolor(DIVERGED_COLOR)
    peak = sweep[PEAK].sel(model=reference)
    mesh = ax.pcolormesh(x, y, _field(peak), norm=_peak_norm(peak.values), cmap="viridis",
                         shading="nearest", rasterized=True)
    _colorbar(fig, mesh, ax, axis_label(f"{reference} peak $|v(L)|$", peak.attrs.get("units", "m")),
              location="bottom", shrink=0.9)
    flagged = _hatch_flagged(ax, x, y, sweep["validity"].sel(model=reference))
    critical = _critical_speed(ax, sweep, x_name, y_name)
    _legend(ax, flagged, critical, extra=[boundary])
    panel_title(ax, 1, f"{reference}: peak tip deflection")
    ax.set_xlabel(_label(x))
    ax.grid(False)
    return fig


def _slices(sweep: xr.Dataset, config: dict):
    """A map of three axes: panels of the first two at ``figure.slices`` values of the third."""
    x_name, y_name, x, y = _axes_of(sweep, config)
    figure = config["figure"]
    third = config["axes"][2]
    count = min(int(figure.get("slices", 4)), sweep[third].size)
    picks = np.unique(np.round(np.linspace(0, sweep[third].size - 1, count)).astype(int))
    departure = figure["kind"] == "departure"
    rows = [figure["model"]] if departure else list(sweep["model"].values)
    if departure:
        field = relative_departure(sweep, figure["model"], figure["reference"])
        values = field.values[np.isfinite(field.values) & (field.values > 0)]
        if values.size == 0:
            raise DatasetError("sweep dataset: no grid point where both models completed "
                                  "with different peaks; nothing to map")
        norm = LogNorm(vmin=max(float(values.min()), 1e-4),
                       vmax=max(float(values.max()), 10 * float(figure["threshold"])))
        label, cmap = (f"|{figure['model']} - {figure['reference']}| / {figure['reference']} "
                       "of the peak $|v(L)|$"), "magma"
    else:
        norm = _peak_norm(sweep[PEAK].values)
        label, cmap = axis_label("Peak $|v(L)|$", sweep[PEAK].attrs.get("units", "m")), "viridis"
    fig, axes = new_figure(len(rows), picks.size, width=2.6 * picks.size + 0.8,
                           height=2.6 * len(rows) + 1.3, sharex=True, sharey=True)
    mesh = None
    for row, model in enumerate(rows):
        for column, index in enumerate(picks):
            ax = axes[row, column]
            ax.set_facecolor(DIVERGED_COLOR)
            at = {third: index}
            if departure:
                values = field.isel(at)
                mesh = ax.pcolormesh(x, y, _field(values.where(np.isfinite(values))), norm=norm,
                                     cmap=cmap, shading="nearest", rasterized=True)
                departs = _field((values > float(figure["threshold"])) | np.isinf(values))
                ax.contour(x, y, departs.astype(float), levels=[0.5], colors=DEPARTURE_COLOR,
                           linewidths=1.3)
            else:
                mesh = ax.pcolormesh(x, y, _field(sweep[PEAK].sel(model=model).isel(at)),
                                     norm=norm, cmap=cmap, shading="nearest", rasterized=True)
            flagged = _hatch_flagged(ax, x, y, sweep["validity"].sel(model=model).isel(at))
            critical = _critical_speed(ax, sweep.isel(at), x_name, y_name)
            if row == 0 and column == 0:
                extra = ([ax.plot([], [], color=DEPARTURE_COLOR,
                                  label=f"departs by {float(figure['threshold']):.0%}")[0]]
                         if departure else [])
                _legend(ax, flagged, critical, extra=extra, below=fig)
            coordinate = sweep[third]
            panel_title(ax, row * picks.size + column,
                        f"{model}, {AXIS_LABELS.get(third, third)} = "
                        f"{float(coordinate[index]):.3g} {coordinate.attrs.get('units', '')}")
            if row == len(rows) - 1:
                ax.set_xlabel(_label(x))
            if column == 0:
                ax.set_ylabel(_label(y))
            ax.grid(False)
    _colorbar(fig, mesh, axes.ravel().tolist(), label)
    return fig
