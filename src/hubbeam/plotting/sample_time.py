"""The sample-time sweep of sampled LQR designs (:mod:`hubbeam.control.sample_time`): spectral radius against Ts.

One panel per gain (the continuous LQR gain through the hold; a discrete LQR redesigned at each
sample time), one colour per design, solid without delay and dashed with one sample of delay (the
delays of the dataset in order of line style); the unit circle's radius 1 as a horizontal line, each
stability boundary as a dot on it, and the sample time ``1/(2 f)`` from which each vibration mode of
the truth plant aliases as a labelled vertical line.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, VARIANT_LINESTYLES, axis_label, new_figure

#: at most this many aliasing marks (the slowest vibration modes): faster ones alias below any sample time swept
ALIASING_MARKS = 4


def plot(sweep: xr.Dataset):
    """Spectral radius against sample time per gain, design and delay (module docstring)."""
    gains = [str(g) for g in sweep["gain"].values]
    fig, axes = new_figure(1, len(gains), height=3.6)
    Ts = sweep["sample_time"].values * 1e3
    aliasing = sweep["aliasing_sample_time"].values * 1e3
    names = [str(n) for n in sweep["truth_mode"].values]
    marks = [(names[k], aliasing[k]) for k in np.argsort(-np.nan_to_num(aliasing, nan=-1.0))
             if np.isfinite(aliasing[k]) and Ts[0] <= aliasing[k] <= Ts[-1]][:ALIASING_MARKS]
    for ax, gain in zip(axes[0], gains):
        for k, design in enumerate(sweep["design"].values):
            color = SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)]
            for d, delay in enumerate(sweep["delay"].values):
                radius = sweep["spectral_radius"].sel(design=design, gain=gain, delay=delay).values
                ax.plot(Ts, radius, color=color, linestyle=VARIANT_LINESTYLES[d % len(VARIANT_LINESTYLES)],
                        label=f"{design}, delay {delay:g}")
                boundary = float(sweep["boundary"].sel(design=design, gain=gain, delay=delay))
                if np.isfinite(boundary):
                    ax.plot(boundary * 1e3, 1.0, "o", color=color, markersize=4)
        ax.axhline(1.0, color="0.3", linewidth=0.8)
        for name, value in marks:
            ax.axvline(value, color="0.55", linewidth=0.7, linestyle=":")
            ax.annotate(f"{name} aliases", (value, 0.02), xycoords=("data", "axes fraction"), rotation=90,
                        fontsize=6, color="0.35", ha="right", va="bottom")
        ax.set_xscale("log")
        ax.set_title(f"{gain} gain" + (" through the hold" if gain == "continuous" else ", redesigned at each Ts"))
        ax.set_xlabel(axis_label("sample time $T_s$", "ms"))
        ax.set_ylabel(axis_label(r"spectral radius $\max|z|$", "1"))
        top = np.nanmax(sweep["spectral_radius"].sel(gain=gain).values)
        ax.set_ylim(max(0.0, np.nanmin(sweep["spectral_radius"].values) - 0.05), min(max(top, 1.05), 2.0) + 0.02)
    axes[0, 0].legend(loc="upper left", fontsize=6)
    return fig
