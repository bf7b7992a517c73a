"""Beyond the paper: TLAM's critical angular velocity over tip mass and tip-mass position.

Reads the eigen dataset ``results/eigen/critical_speeds.nc`` (``critical_speed`` over ``model``,
``tip_mass``, ``position``; NaN where ``K22`` stays positive definite, always for FOAM). One curve
per tip mass against position, with the paper's three quoted values (Sections 4.2, 4.4) and the
continuum-beam value at the tip (``continuum_tlam_critical_speed_at_tip``) as markers; with four or
more tip masses a second panel maps the critical speed over the (position, mass) plane.
"""

from __future__ import annotations

import xarray as xr

from hubbeam.model import printed as paper
from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, panel_title
from hubbeam.results.reader import DatasetError

MAP_MIN_MASSES = 4


def plot(critical: xr.Dataset, model: str = "TLAM"):
    """The critical-speed figure from the ``critical`` speed sweep of :mod:`hubbeam.model.eigen`."""
    ds = critical
    if "critical_speed" not in ds.data_vars:
        raise DatasetError("critical-speed dataset has no variable 'critical_speed' "
                              f"(has: {', '.join(sorted(ds.data_vars))})")
    speed = ds["critical_speed"].sel(model=model)
    masses = speed["tip_mass"].values
    positions = speed["position"].values
    as_map = len(masses) >= MAP_MIN_MASSES
    fig, axes = new_figure(1, 2 if as_map else 1, width=7.0 if as_map else None, height=3.4,
                           sharex=False)
    ax = axes[0, 0]
    beam_end = float(positions[-1])
    for k, mass in enumerate(masses):
        color = SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)]
        ax.plot(positions, speed.sel(tip_mass=mass).values, color=color,
                label=f"{model}, n = {ds.attrs.get('n_modes', '?')}, $m_t$ = {mass:g} kg")
        if "continuum_tlam_critical_speed_at_tip" in ds and model == "TLAM" and mass > 0:
            ax.plot(beam_end, float(ds["continuum_tlam_critical_speed_at_tip"].sel(tip_mass=mass)),
                    marker="o", markerfacecolor="none", color=color, linestyle="none")
    printed = [(0.0 if m == 0 else beam_end, v) for m, v in paper.CRITICAL_SPEEDS_TLAM.items()]
    ax.plot(*zip(*printed), "kx", markersize=6, label="paper (Sections 4.2, 4.4)")
    if "continuum_tlam_critical_speed_at_tip" in ds and model == "TLAM":
        ax.plot([], [], "ko", markerfacecolor="none", label="continuum beam, mass at the tip")
    title = f"Critical angular velocity of {model}"
    if as_map:
        panel_title(ax, 0, title)
    else:  # a single panel needs no letter
        ax.set_title(title)
    ax.set_xlabel(axis_label("Tip-mass position $l$", "m"))
    ax.set_ylabel(axis_label("$\\Omega_c$", "rad s-1"))
    ax.legend(loc="lower left")
    if as_map:
        ax = axes[0, 1]
        mesh = ax.contourf(positions, masses, speed.values, levels=20, cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=axis_label("$\\Omega_c$", "rad s-1"))
        panel_title(ax, 1, f"{model} critical speed over position and mass")
        ax.set_xlabel(axis_label("Tip-mass position $l$", "m"))
        ax.set_ylabel(axis_label("Tip mass $m_t$", "kg"))
        ax.grid(False)
    return fig
