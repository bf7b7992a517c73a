"""Bode diagrams from the rig's input (the hub torque of a free hub, or its drive's voltage) to the
hub angle, the tip deflection ``v(L)``
and the tip's arc position ``(rA + L) theta + v(L)``, for each model at several hub speeds.

Drawn from :func:`hubbeam.linear.datasets.bode` (computed with python-control): one column per
speed, a magnitude and a phase row per output, one colour per model. A speed at which a model's
plant is unstable (TLAM beyond its critical speed) is named in the panel: its curve is the
frequency response of the transfer function, not a measurable steady state.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.campbell_tracked import one_plant
from hubbeam.plotting.style import axis_label, model_style, new_figure, units_tex

INPUTS = {"torque": "hub torque", "voltage": "drive voltage"}
OUTPUT_NAMES = {"hub_angle": r"hub angle $\theta$", "tip_deflection": r"tip deflection $v(L)$",
                "tip_arc": r"tip arc $(r_A + L)\theta + v(L)$"}


def plot(bode: xr.Dataset, tip_mass: float | str | None = None):
    """Magnitude and phase against frequency: rows per output, columns per speed."""
    ds, where = one_plant(bode, tip_mass, "Bode")
    outputs = [name.removesuffix("_magnitude") for name in ds.data_vars if name.endswith("_magnitude")]
    speeds = ds["speed"].values
    # the rig's input: the drive's voltage (magnitudes per volt) or the hub torque
    source = "voltage" if ds[f"{outputs[0]}_magnitude"].attrs.get("units", "").endswith("V-1") else "torque"
    fig, axes = new_figure(2 * len(outputs), len(speeds), width=2.6 * len(speeds) + 0.8,
                           height=1.7 * 2 * len(outputs), sharex=True, sharey="row")
    omega = ds["frequency"].values
    for column, speed in enumerate(speeds):
        unstable = []
        for model in ds["model"].values:
            one = ds.sel(model=model, speed=speed)
            style = model_style(str(model))
            if not bool(one["stable"]):
                unstable.append(str(model))
            for o, output in enumerate(outputs):
                axes[2 * o, column].loglog(omega, one[f"{output}_magnitude"], **style,
                                           label=str(model) if o == 0 and column == 0 else None)
                axes[2 * o + 1, column].semilogx(omega, one[f"{output}_phase"], **style)
        note = f" ({', '.join(unstable)} unstable)" if unstable else ""
        axes[0, column].set_title(rf"$\Omega$ = {speed:g} rad/s{note}")
        axes[-1, column].set_xlabel(axis_label(r"frequency $\omega$", "rad s-1"))
    for o, output in enumerate(outputs):
        units = ds[f"{output}_magnitude"].attrs.get("units", "")
        axes[2 * o, 0].set_ylabel(f"|{OUTPUT_NAMES.get(output, output)} / {source}|\n({units_tex(units)})",
                                  fontsize=7)
        axes[2 * o + 1, 0].set_ylabel("phase (deg)", fontsize=7)
        phase = ds[f"{output}_phase"].values
        low, high = np.floor(np.nanmin(phase) / 180.0), np.ceil(np.nanmax(phase) / 180.0)
        step = 180 if high - low <= 6 else 360  # ticks at whole half turns, or whole turns
        axes[2 * o + 1, 0].set_yticks(np.arange(low * 180, high * 180 + 1, step))
    fig.suptitle(f"{INPUTS[source]} to hub angle, tip deflection and tip arc, free hub, {where}", fontsize=9)
    fig.legend(*axes[0, 0].get_legend_handles_labels(), loc="outside lower center", ncols=4)
    return fig
