"""Poles and zeros against hub speed and pole-zero maps, the hub torque of a free hub as the input.

Drawn from :func:`hubbeam.linear.datasets.poles_zeros`. Top row, one panel per model: the
frequencies ``|Im|`` of the poles (x) and of the collocated zeros (hub torque to hub angle, o,
which are the poles with the hub held) against speed, and the magnitude of the smallest
right-half-plane zero of the tip's arc position (black triangle, non-minimum phase). TLAM's first
pole (and collocated zero) reaches 0 at its critical speed, where a real pair takes over (the real
part of its growing pole: +). Bottom row: pole-zero maps of the tip arc output at three speeds,
all models.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.lines import Line2D

from hubbeam.plotting.campbell_tracked import one_plant
from hubbeam.plotting.style import axis_label, model_style, new_figure, panel_title

#: the largest |root| drawn (rad s-1): the first bending modes and the lowest tip zeros
LIMIT = 60.0
#: real parts above this fraction of the drawn range mark a growing pole (rounding leaves the
#: real parts of undamped poles at 1e-12 s-1)
GROWING = 1e-6


def _near(values, limit):
    values = values[np.isfinite(values)]
    return values[np.abs(values) <= limit]


def plot(poles_zeros: xr.Dataset, tip_mass: float | str | None = None, limit: float = LIMIT):
    """Root frequencies against speed (top, per model) and tip-arc pole-zero maps (bottom)."""
    ds, where = one_plant(poles_zeros, tip_mass, "poles and zeros")
    models = ds["model"].values
    fig, axes = new_figure(2, len(models), width=2.2 * len(models), height=5.4, sharex=False)
    speed = ds["speed"].values
    rig = "driven" if "driven_pole_real" in ds else "free"  # the poles of the rig's input: through a drive
    for column, model in enumerate(models):
        ax = axes[0, column]
        one = ds.sel(model=model)
        style = model_style(str(model))
        for k, value in enumerate(speed):
            poles = one[f"{rig}_pole_real"][k].values + 1j * one[f"{rig}_pole_imag"][k].values
            zeros = (one["zero_real"].sel(output="hub_angle")[k].values
                     + 1j * one["zero_imag"].sel(output="hub_angle")[k].values)
            p = _near(np.abs(poles.imag[poles.imag >= 0]), limit)
            z = _near(np.abs(zeros.imag[zeros.imag >= 0]), limit)
            ax.plot(np.full(p.size, value), p, "x", color=style["color"], markersize=3,
                    label="poles" if k == 0 else None)
            ax.plot(np.full(z.size, value), z, "o", mfc="none", color="0.35", markersize=3,
                    markeredgewidth=0.6, label="zeros (hub angle)" if k == 0 else None)
            growing = _near(poles.real[poles.real > GROWING * limit], limit)
            ax.plot(np.full(growing.size, value), growing, "+", color="#D55E00", markersize=4,
                    label="Re of a growing pole" if growing.size else None)
        rhp = one["lowest_rhp_zero"].sel(output="tip_arc")
        ax.plot(speed, rhp.where(rhp <= limit), "^", color="k", markersize=2.5,
                label="RHP zero (tip arc)")
        ax.set_ylim(0.0, limit)
        panel_title(ax, column, f"{model}, {where}")
        ax.set_xlabel(axis_label(r"hub speed $\Omega$", "rad s-1"))
    axes[0, 0].set_ylabel(axis_label("|Im| of root, or |z|", "rad s-1"))
    picks = np.unique(np.linspace(0, speed.size - 1, min(3, len(models), speed.size)).round().astype(int))
    for column, k in enumerate(picks):
        ax = axes[1, column]
        for model in models:
            one = ds.sel(model=model).isel(speed=k)
            style = model_style(str(model))
            poles = one[f"{rig}_pole_real"].values + 1j * one[f"{rig}_pole_imag"].values
            zeros = (one["zero_real"].sel(output="tip_arc").values
                     + 1j * one["zero_imag"].sel(output="tip_arc").values)
            poles, zeros = (v[np.isfinite(v) & (np.abs(v) <= limit)] for v in (poles, zeros))
            ax.plot(poles.real, poles.imag, "x", color=style["color"], markersize=4, label=str(model))
            ax.plot(zeros.real, zeros.imag, "o", mfc="none", color=style["color"], markersize=4)
        ax.axvline(0.0, color="0.5", linewidth=0.5)
        ax.set_xlim(-limit, limit)
        ax.set_ylim(-limit, limit)
        ax.set_aspect("equal")
        panel_title(ax, len(models) + column, rf"tip arc, $\Omega$ = {speed[k]:g} rad/s")
        ax.set_xlabel(axis_label("Re s", "rad s-1"))
    axes[1, 0].set_ylabel(axis_label("Im s", "rad s-1"))
    for ax in axes[1, picks.size:]:
        ax.set_visible(False)
    # one entry per marker of the top row (in a neutral colour: the panels give the models'
    # colours), then the models of the maps
    legend = {}
    for ax in axes[0]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, Line2D([], [], linestyle="none", marker=handle.get_marker(),
                                            color="0.3", mfc=handle.get_mfc(), markersize=4))
    map_handles, map_labels = axes[1, 0].get_legend_handles_labels()
    fig.legend(list(legend.values()) + map_handles,
               list(legend) + [f"{m}: x pole, o tip-arc zero" for m in map_labels],
               loc="outside upper center", ncols=4, fontsize=7)
    return fig
