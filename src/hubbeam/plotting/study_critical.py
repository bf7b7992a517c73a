"""Critical hub speeds of a study's beam against tip-mass position, one curve per tip mass.

Reads the dataset of :func:`hubbeam.model.eigen.critical_speed_sweep`: the speed at which the
transverse stiffness K22 of TLAM (or FOAM) becomes singular (Sections 4.2, 4.4); models without
any critical speed up to the search limit (FOAM stiffens) are named in the title instead.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, model_style, new_figure


def plot(critical: xr.Dataset):
    """Critical speed against tip-mass position per tip mass and model."""
    fig, axes = new_figure(1, 1, height=3.4)
    ax = axes[0, 0]
    speed = critical["critical_speed"]
    positions = speed["position"].values
    none = []
    for model in speed["model"].values:
        values = speed.sel(model=model)
        if not np.isfinite(values.values).any():
            none.append(str(model))
            continue
        for k, mass in enumerate(speed["tip_mass"].values):
            style = model_style(str(model)) | {"color": SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)]}
            ax.plot(positions, values.sel(tip_mass=mass).values, **style,
                    label=f"{model}, $m_t$ = {mass:g} kg")
    search_max = float(critical.attrs.get("critical_speed_search_max", np.nan))
    title = "Critical hub speed"
    if none:
        title += f" (none below {search_max:g} rad/s: {', '.join(none)})"
    ax.set_title(title)
    ax.set_xlabel(axis_label("tip-mass position $l$", "m"))
    ax.set_ylabel(axis_label(r"$\Omega_c$", "rad s-1"))
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=7)
    return fig
