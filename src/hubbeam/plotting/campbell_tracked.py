"""Tracked, damped Campbell diagram: frequency and damping ratio against hub speed, held and free hub.

Drawn from the dataset of :func:`hubbeam.linear.datasets.campbell`: one colour per model, each
tracked bending mode one curve (the axial modes, above 150 Hz for the paper's beam, and the rigid
hub mode are left out), labelled at the right end of the last model's curve by its content at the
first speed. The speed
range where a model has a growing mode is shaded in its colour, and the critical speed of ``K22``
(Eq. 31) marked; a divergent mode has frequency 0 (off the logarithmic axis) and damping ratio -1.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.fig09 import labelled
from hubbeam.plotting.style import LABEL_BOX, axis_label, model_style, new_figure, panel_title

#: damping ratios below this are rounding (an undamped mode's -Re lambda / |lambda| of 1e-14), drawn as 0
ROUNDING = 1e-9
HUB_TITLES = {"held": "hub held (speed prescribed)", "free": "free hub (torque input)",
              "driven": "free hub through its drive (voltage input)"}


def one_plant(ds: xr.Dataset, tip_mass: float | str | None, what: str) -> tuple[xr.Dataset, str]:
    """``ds`` of one plant and a caption fragment naming it: a study's plant (its ``plant``
    coordinate), or one tip mass of the paper's grid (kg; the first one by default, ``"largest"``
    the largest; a clear error if absent)."""
    if "plant" in ds.dims:
        return ds.isel(plant=0), f"plant {ds['plant'].values[0]}"
    masses = ds["tip_mass"].values
    mass = float({None: masses[0], "largest": masses.max()}.get(tip_mass, tip_mass))
    labelled(ds, next(iter(ds.data_vars)), what, tip_mass=mass)
    where = f"{mass:g} kg tip mass" if mass > 0 else "no tip mass"
    return ds.sel(tip_mass=mass, method="nearest"), where


def plot(campbell: xr.Dataset, tip_mass: float | str | None = None):
    """Frequency (top) and damping ratio (bottom) against hub speed, held and free hub."""
    ds, where = one_plant(campbell, tip_mass, "Campbell")
    hubs = ds["hub"].values
    fig, axes = new_figure(2, len(hubs), width=3.5 * len(hubs), height=5.6, sharex=True)
    speed = ds["speed"].values
    for column, hub in enumerate(hubs):
        top, bottom = axes[0, column], axes[1, column]
        for model in ds["model"].values:
            one = ds.sel(model=model, hub=hub)
            style = model_style(str(model))
            bending = [m for m in one["mode"].values
                       if str(one["mode_label"].sel(mode=m).item()).startswith("bending")]
            for index, mode in enumerate(bending):
                curve = one.sel(mode=mode)
                label = str(model) if index == 0 else None
                top.plot(speed, np.where(curve["frequency"] > 0, curve["frequency"], np.nan),
                         **style, label=label)
                ratio = curve["damping_ratio"].values
                bottom.plot(speed, np.where(np.abs(ratio) < ROUNDING, 0.0, ratio), **style)
                drawn = np.flatnonzero(curve["frequency"].values > 0)
                if model == ds["model"].values[-1] and drawn.size:
                    last = drawn[-1]
                    top.annotate(str(curve["mode_label"].item()),
                                 xy=(speed[last], float(curve["frequency"][last])), xytext=(2, 0),
                                 textcoords="offset points", fontsize=6, va="center", bbox=LABEL_BOX)
            start = float(one["unstable_from"])
            if np.isfinite(start):
                for ax in (top, bottom):
                    ax.axvspan(start, speed[-1], color=style["color"], alpha=0.12, linewidth=0)
                bottom.annotate(f"{model} unstable", xy=(start, 0.04), xycoords=("data", "axes fraction"),
                                xytext=(2, 0), textcoords="offset points", fontsize=7, va="bottom",
                                color=style["color"], bbox=LABEL_BOX)
            critical = float(ds["critical_speed"].sel(model=model))
            if np.isfinite(critical):
                for ax in (top, bottom):
                    ax.axvline(critical, color=style["color"], linewidth=0.7, linestyle=":")
        top.set_yscale("log")
        panel_title(top, column, HUB_TITLES.get(str(hub), str(hub)))
        panel_title(bottom, len(hubs) + column, "damping ratio (-1: divergent)")
        bottom.set_xlabel(axis_label(r"hub speed $\Omega$", "rad s-1"))
    axes[0, 0].set_ylabel(axis_label("frequency", "Hz"))
    axes[1, 0].set_ylabel(axis_label(r"damping ratio $\zeta$", "1"))
    fig.legend(*axes[0, 0].get_legend_handles_labels(), loc="outside upper center", ncols=4)
    fig.suptitle(f"Campbell diagram, {where}", fontsize=9, y=0.0, va="bottom")
    return fig
