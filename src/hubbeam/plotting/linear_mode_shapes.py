"""First mode shapes along the span, at rest and at the highest speed, held and free hub.

Drawn from :func:`hubbeam.linear.datasets.mode_shapes`: the transverse shape ``v(x) = f2(x) q2``
of each of the first vibration modes (colour, by frequency at rest; labelled by its content
there), one line style per model, scaled to ``max |v| = 1``; a study's tip body a short bar at its
position, turned by its rotation in the mode. The real part is drawn (a gyroscopic
mode's imaginary part, the phase lag along the span, is small for the bending modes).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.campbell_tracked import HUB_TITLES, one_plant
from hubbeam.plotting.style import SEQUENCE_COLORS, VARIANT_LINESTYLES, axis_label, new_figure, panel_title


def plot(shapes: xr.Dataset, tip_mass: float | str | None = None):
    """Mode shapes: rows the first and the last speed, columns the hub conditions."""
    ds, where = one_plant(shapes, tip_mass, "mode shapes")
    speeds, hubs = ds["speed"].values, ds["hub"].values
    fig, axes = new_figure(len(speeds), len(hubs), width=7.0, height=2.6 * len(speeds), sharex=True)
    x = ds["x"].values
    for row, speed in enumerate(speeds):
        for column, hub in enumerate(hubs):
            ax = axes[row, column]
            for m, model in enumerate(ds["model"].values):
                one = ds.sel(model=model, hub=hub, speed=speed)
                for r, rank in enumerate(one["rank"].values):
                    label = None
                    if m == 0:
                        label = f"mode {rank}: {one['mode_label'].sel(rank=rank).item()}"
                    ax.plot(x, one["shape"].sel(rank=rank), color=SEQUENCE_COLORS[r % len(SEQUENCE_COLORS)],
                            linestyle=VARIANT_LINESTYLES[m % len(VARIANT_LINESTYLES)], label=label)
            if "body_rotation" in ds:
                _body(ax, ds.sel(hub=hub, speed=speed), float(ds.attrs["tip_position_m"]), x)
            ax.axhline(0.0, color="0.5", linewidth=0.5)
            panel_title(ax, row * len(hubs) + column,
                        rf"{HUB_TITLES.get(str(hub), str(hub))}, $\Omega$ = {speed:g} rad/s")
        axes[row, 0].set_ylabel(axis_label(r"$v(x)$ / max $|v|$", "1"))
    for ax in axes[-1]:
        ax.set_xlabel(axis_label("distance from the clamp $x$", "m"))
    for m, model in enumerate(ds["model"].values):  # legend entries of the line styles
        axes[0, 0].plot([], [], color="0.2", linestyle=VARIANT_LINESTYLES[m % len(VARIANT_LINESTYLES)],
                        label=str(model))
    fig.suptitle(f"transverse mode shapes, {where}", fontsize=9)
    fig.legend(*axes[0, 0].get_legend_handles_labels(), loc="outside lower center", ncols=4)
    return fig


def _body(ax, ds: xr.Dataset, position: float, x) -> None:
    """The tip body at ``position`` in each mode of the first model: a short bar through its
    deflection turned by its rotation (the shape's slope there plus the hub's or root's angle)."""
    one = ds.isel(model=0)
    half = 0.04 * (x[-1] - x[0])
    for r, rank in enumerate(one["rank"].values):
        deflection = float(np.interp(position, x, one["shape"].sel(rank=rank).values))
        rotation = float(one["body_rotation"].sel(rank=rank))
        ax.plot([position - half, position + half], [deflection - half * rotation, deflection + half * rotation],
                color=SEQUENCE_COLORS[r % len(SEQUENCE_COLORS)], linewidth=3.0, solid_capstyle="butt", alpha=0.6,
                label="tip body, turned by its rotation" if r == 0 else None)
