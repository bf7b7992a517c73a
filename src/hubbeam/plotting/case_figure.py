"""The figure of one simulation of a study: tip deflection, hub speed, hub torque and energy.

Panels: (a) the tip deflection v(L) = f2(L) q2; (b) the hub angular velocity theta'; (c) the torque
on the hub (applied, or required by a prescribed hub); (d) the change of the total mechanical
energy T + U since t = 0 and, where the dataset has them, the work of the hub torque and the
damping dissipation, whose difference it equals (energy balance). The end of the maneuver and a
divergence are marked.
"""

from __future__ import annotations

import xarray as xr

from hubbeam.plotting.style import (
    axis_label,
    mark_time,
    model_style,
    new_figure,
    panel_title,
)
from hubbeam.study.summary import dataset_maneuver, maneuver_end

#: quantity drawn per panel -> (variable of the simulation dataset, label with units)
SERIES = {"tip": ("tip_transverse", axis_label("tip deflection $v(L)$", "m")),
          "speed": ("theta_dot", axis_label(r"hub speed $\dot\theta$", "rad s-1")),
          "torque": ("hub_torque", axis_label(r"hub torque $\tau$", "N m"))}


def mark_events(ax, ds: xr.Dataset, end: float) -> None:
    """Mark the end of the maneuver and, for a diverged run, the divergence time."""
    if end < float(ds["time"].values[-1]):
        mark_time(ax, end, f"maneuver end {end:g} s")
    if int(ds.attrs["diverged"]) == 1:
        mark_time(ax, float(ds.attrs["diverged_at_s"]), "diverged", color="#D55E00")


def plot(case: str, ds: xr.Dataset):
    """The four-panel figure of simulation ``case`` from its dataset ``ds``."""
    maneuver = dataset_maneuver(ds)
    fig, axes = new_figure(4, 1, height=7.0)
    axes = axes[:, 0]
    t = ds["time"].values
    style = model_style(str(ds.attrs["model"]))
    end = maneuver_end(maneuver)
    for index, (name, label) in enumerate(SERIES.values()):
        axes[index].plot(t, ds[name].values, **style)
        axes[index].set_ylabel(label)
        mark_events(axes[index], ds, end)
    ax = axes[3]
    energy = ds["energy"].values
    ax.plot(t, energy - energy[0], label="$E(t) - E(0)$", **style)
    if "work" in ds.data_vars:
        net = ds["work"].values - (ds["dissipated_energy"].values if "dissipated_energy" in ds else 0.0)
        ax.plot(t, net, color="0.2", linestyle=":", label="work - dissipated")
        ax.legend(loc="best")
    ax.set_ylabel(axis_label("energy change", "J"))
    ax.set_xlabel(axis_label("time $t$", "s"))
    panel_title(axes[0], 0, f"{case}: {ds.attrs['model']}, n = {int(ds.attrs['n_modes'])}, "
                f"{maneuver['kind']}")
    return fig
