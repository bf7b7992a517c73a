"""Campbell diagram: vibration frequencies against hub speed, TLAM against FOAM.

Frequencies of the transverse subsystem ``(K22(Omega), M2)`` (the interpretation of Table 2), one
panel per tip mass at the beam tip, every mode of the model drawn (the legend gives the mode
count n). TLAM softens and loses its first frequency at the critical speed (marked); FOAM
stiffens. Beyond the critical speed TLAM's first mode is divergent and has no frequency.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.fig09 import labelled
from hubbeam.plotting.style import LABEL_BOX, axis_label, model_style, new_figure, panel_title


def plot(campbell: xr.Dataset, critical: xr.Dataset):
    """Campbell diagram from the ``campbell`` and ``critical`` datasets of :mod:`hubbeam.model.eigen`."""
    masses = campbell["tip_mass"].values
    fig, axes = new_figure(1, len(masses), width=2.8 * len(masses), height=3.2, sharex=True)
    axes = axes[0]
    tip = float(campbell.attrs["tip_position_m"])
    for index, mass in enumerate(masses):
        ax = axes[index]
        for model in campbell["model"].values:
            frequency = campbell["frequency"].sel(model=model, tip_mass=mass)
            n = frequency.sizes["mode"]
            for mode in frequency["mode"].values:
                ax.plot(frequency["speed"], frequency.sel(mode=mode), **model_style(str(model)),
                        label=f"{model}, n = {n} (modes 1-{n})" if mode == 1 else None)
        omega_c = float(labelled(critical, "critical_speed", "critical", model="TLAM",
                                 tip_mass=mass, position=tip))
        if np.isfinite(omega_c) and omega_c <= float(campbell["speed"].max()):
            ax.axvline(omega_c, color="0.3", linewidth=0.7, linestyle=":")
            ax.annotate(rf"TLAM $\Omega_c$ = {omega_c:.3f} rad/s", xy=(omega_c, 0.02),
                        xycoords=("data", "axes fraction"), xytext=(3, 0),
                        textcoords="offset points", ha="left", fontsize=7, rotation=90,
                        bbox=LABEL_BOX)
        ax.set_yscale("log")
        what = f"$m_t$ = {mass:g} kg at $l$ = {tip:g} m" if mass > 0 else "no tip mass"
        panel_title(ax, index, what)
        ax.set_xlabel(axis_label(r"hub speed $\Omega$", "rad s-1"))
    axes[0].set_ylabel(axis_label("frequency", "Hz"))
    # one legend above the panels: every panel is full of curves
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside upper center", ncols=2)
    return fig
