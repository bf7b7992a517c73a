"""The first transverse mode shapes of a study's beam, at rest and at the top of its speed grid.

Reads the dataset of :func:`hubbeam.model.shapes.beam_dataset`: one panel per hub speed, one colour per
mode, one dash pattern per tip mass (at the tip), each shape scaled to a largest deflection of 1
with the tip deflection positive; FOAM's shapes (at rest TLAM's are the same;
beyond its critical speed TLAM has no first mode). The legend gives each mode's frequency.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, VARIANT_LINESTYLES, axis_label, new_figure, panel_title

#: the model whose shapes are drawn
MODEL = "FOAM"


def plot(beam: xr.Dataset):
    """Mode shapes w(x), one panel per speed."""
    speeds = beam["speed"].values
    masses = beam["tip_mass"].values
    height = 3.0 + 0.13 * beam.sizes["mode"] * len(masses)  # room for the legends below the panels
    fig, axes = new_figure(1, len(speeds), width=3.2 * len(speeds), height=height, sharex=True, sharey=True)
    shapes = beam["shape"].sel(model=MODEL)
    frequency = beam["frequency"].sel(model=MODEL)
    for index, speed in enumerate(speeds):
        ax = axes[0, index]
        for k, mass in enumerate(masses):
            for mode in beam["mode"].values:
                w = shapes.sel(speed=speed, tip_mass=mass, mode=mode)
                f = float(frequency.sel(speed=speed, tip_mass=mass, mode=mode))
                if not np.isfinite(f):
                    continue
                ax.plot(beam["x"], w, color=SEQUENCE_COLORS[(mode - 1) % len(SEQUENCE_COLORS)],
                        linestyle=VARIANT_LINESTYLES[k % len(VARIANT_LINESTYLES)],
                        label=f"{mode}, $m_t$ = {mass:g} kg: {f:.3g} Hz")
        ax.axhline(0.0, color="0.6", linewidth=0.6)
        panel_title(ax, index, "at rest" if speed == 0.0 else rf"$\Omega$ = {speed:g} rad/s")
        ax.set_xlabel(axis_label("distance from the root $x$", "m"))
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22), fontsize=6,
                  title="mode, tip mass: frequency", title_fontsize=6)
    axes[0, 0].set_ylabel(f"{MODEL} mode shape $w(x)$ (largest 1)")
    return fig
