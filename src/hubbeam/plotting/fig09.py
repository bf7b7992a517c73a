"""Fig. 9: the dominant (lowest) eigenvalue of K22 against tip-mass position and hub speed.

The paper does not say at which angular velocity its curves are drawn (reproduction note 10).
Panels (a), (b) show the lowest eigenvalue of TLAM's ``K22 = K2 - Omega^2 M2`` (tip-mass term
included, Section 4.4) over position ``l`` and speed ``Omega`` for each tip mass, with the critical
speed ``Omega_c(l)`` (where it crosses zero) drawn on top and the paper's values at ``l = L``
marked; panel (c) shows single curves against position at one stated speed. Eigenvalues depend on
the mode normalisation (note 7): modes of unit modal mass of the bare beam, units s^-2.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.colors import TwoSlopeNorm

from hubbeam.model import printed as paper
from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, panel_title

EIGENVALUE_LABEL = r"$\lambda_{\min}(K_{22})$ (s$^{-2}$), modes of unit modal mass"


def labelled(ds: xr.Dataset, variable: str, what: str, **selection) -> xr.DataArray:
    """``ds[variable]`` at the labels ``selection`` (numbers matched to 1e-9), or a clear error."""
    if variable not in ds.data_vars:
        raise ValueError(f"{what} dataset has no variable {variable!r}")
    data = ds[variable]
    for name, value in selection.items():
        labels = ds[name].values
        if isinstance(value, str):
            found = value in labels
        else:
            found = np.any(np.isclose(labels, value, rtol=1e-9, atol=1e-12))
        if not found:
            raise ValueError(f"{what} dataset has no {name} = {value!r}; "
                             f"available: {[label.item() for label in labels]}")
        data = data.sel({name: value}, method=None if isinstance(value, str) else "nearest")
    return data


def plot(k22: xr.Dataset, critical: xr.Dataset, masses=(0.1, 0.5), speed: float = 2.0,
         model: str = "TLAM"):
    """Fig. 9 from the ``k22`` sweep and the ``critical`` speed sweep of :mod:`hubbeam.model.eigen`.

    ``masses`` (kg) get one map each; ``speed`` (rad/s, a grid value) is the hub speed of the
    single curves of the last panel.
    """
    fig, axes = new_figure(1, len(masses) + 1, width=3.0 * (len(masses) + 1), height=3.6,
                           sharex=True)
    axes = axes[0]
    maps = [labelled(k22, "dominant_eigenvalue", "k22", model=model, tip_mass=mass)
            for mass in masses]
    limit = max(float(np.nanmax(np.abs(dominant.values))) for dominant in maps)
    norm = TwoSlopeNorm(0.0, -limit, limit)
    for index, (mass, dominant) in enumerate(zip(masses, maps)):
        ax = axes[index]
        mesh = ax.pcolormesh(dominant["position"], dominant["speed"],
                             dominant.transpose("speed", "position").values, shading="auto",
                             cmap="RdBu", norm=norm, rasterized=True)
        omega_c = labelled(critical, "critical_speed", "critical", model=model, tip_mass=mass)
        ax.plot(omega_c["position"], omega_c, color="k", label=r"critical speed $\Omega_c(l)$")
        printed = paper.CRITICAL_SPEEDS_TLAM.get(mass)
        if printed is not None and model == "TLAM":
            ax.plot([float(k22["position"].max())], [printed], "x", color="k", clip_on=False,
                    label=f"paper, $l = L$: {printed:g} rad/s")
        ax.axhline(speed, color="0.3", linewidth=0.7, linestyle=":",
                   label=rf"$\Omega$ = {speed:g} rad/s (panel ({chr(ord('a') + len(masses))}))")
        panel_title(ax, index, f"{model}, $m_t$ = {mass:g} kg")
        ax.set_xlabel(axis_label("tip-mass position $l$", "m"))
        ax.set_ylabel(axis_label(r"hub speed $\Omega$", "rad s-1"))
        ax.legend(loc="lower left")
    fig.colorbar(mesh, ax=list(axes[:len(masses)]), label=EIGENVALUE_LABEL, location="bottom",
                 shrink=0.6, aspect=40)
    ax = axes[-1]
    for index, mass in enumerate(masses):
        curve = labelled(k22, "dominant_eigenvalue", "k22", model=model, tip_mass=mass,
                         speed=speed)
        ax.plot(curve["position"], curve, color=SEQUENCE_COLORS[index],
                label=f"{model}, n = {k22.attrs.get('n_modes', '?')}, $m_t$ = {mass:g} kg")
    ax.axhline(0.0, color="k", linewidth=0.7)
    panel_title(ax, len(masses), rf"{model} at $\Omega$ = {speed:g} rad/s")
    ax.set_xlabel(axis_label("tip-mass position $l$", "m"))
    ax.set_ylabel(EIGENVALUE_LABEL)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 0.2))  # below the curves, above the zero line
    return fig
