"""The figure of the LQR designs of a study against design speed (``hubbeam.study.trust``).

Panels: peak tip deflection, residual vibration after the spin-up, settling time of v(L) and
peak hub torque, each against the design speed (the final speed of the spin-up). One colour per
design model; solid: the controller on the reference model (CFOAM), dashed: on its own design
model (its prediction). A cross on the speed axis marks a loop that went unstable. A measure no
run has (no run settled within its time, say) gets no panel; the figure's note names it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, panel_title
from hubbeam.study.trust import MEASURES, REFERENCE_MODEL, design_table

#: panel labels of the measures: (quantity, unit)
LABELS = {"peak_tip_deflection_m": ("peak $|v(L)|$", "m"),
          "residual_vibration_m": ("residual $|v(L)|$", "m"),
          "settling_time_s": ("settling time of $v(L)$", "s"),
          "peak_torque_Nm": (r"peak $|\tau|$", "N m")}


def plot(name: str, datasets: Mapping[str, xr.Dataset]):
    """Draw the designs of ``datasets`` (every run of the study; the designed ones are used)."""
    table = design_table(datasets)
    runs_of = [row[which] for row in table for which in ("reference", "own") if row[which]]
    measures = [key for key in MEASURES if any(math.isfinite(run[key]) for run in runs_of)] or list(MEASURES[:1])
    fig, axes = new_figure(len(measures), 1, height=2.0 * len(measures))
    axes = axes[:, 0]
    designs = list(dict.fromkeys(row["design_model"] for row in table))
    for k, design in enumerate(designs):
        rows = [row for row in table if row["design_model"] == design]
        color = SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)]
        for which, style, label in (("reference", "-o", f"designed on {design}, run on {REFERENCE_MODEL}"),
                                    ("own", "--s", f"designed on {design}, run on {design}")):
            runs = [(row["design_speed"], row[which]) for row in rows if row[which]]
            if not runs:  # no such run: no curve and no legend entry
                continue
            speeds = [speed for speed, _ in runs]
            for ax, key in zip(axes, measures):
                ax.plot(speeds, [run[key] for _, run in runs], style, color=color, markersize=4,
                        fillstyle="none" if which == "own" else "full",
                        label=label if key == measures[0] else None)
            unstable = [speed for speed, run in runs if not run["stable"]]
            if unstable:
                axes[0].plot(unstable, [0.0] * len(unstable), "x", color=color, markersize=9,
                             clip_on=False, label=f"unstable ({design} design on "
                             f"{REFERENCE_MODEL if which == 'reference' else design})")
    speeds = sorted({row["design_speed"] for row in table})
    for ax, key in zip(axes, measures):
        ax.set_ylabel(axis_label(*LABELS[key]))
        ax.set_ylim(bottom=0.0)
        if len(speeds) == 1:  # one design speed: the axis from rest, not a sliver around it
            ax.set_xlim(0.0, 1.25 * speeds[0] if speeds[0] > 0 else 1.0)
    axes[-1].set_xlabel(axis_label(r"design speed = final speed $\omega_f$", "rad s$^{-1}$"))
    panel_title(axes[0], 0, f"LQR designs of {name}")
    axes[0].legend(loc="best", fontsize=6)
    missing = [LABELS[key][0] for key in MEASURES if key not in measures]
    if missing:
        fig.text(0.01, 0.005, "not drawn, no run has a value: " + "; ".join(missing), fontsize=6)
    return fig
