"""The figure of one simulation of a study: tip deflection, hub speed, hub torque and energy.

Panels: (a) the tip deflection v(L) = f2(L) q2; (b) the hub angular velocity theta' (with a
compliant root the hub's phi' and the beam root's theta', each named); (c) the torque
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
from hubbeam.results.reader import (
    attr,
    diverged_at,
    left_range_at,
    maneuver,
    maneuver_end,
    model,
    n_modes,
    times,
    variable,
)

#: quantity drawn per panel -> (variable of the simulation dataset, label with units)
SERIES = {"tip": ("tip_transverse", axis_label("tip deflection $v(L)$", "m")),
          "speed": ("theta_dot", axis_label(r"hub speed $\dot\theta$", "rad s-1")),
          "torque": ("hub_torque", axis_label(r"hub torque $\tau$", "N m"))}


def mark_events(ax, case: str, ds: xr.Dataset, end: float) -> None:
    """Mark the end of the maneuver and, for a run stopped early, its stop: diverged, or left
    the range of the models (:mod:`hubbeam.model.validity`)."""
    if end < float(times(ds)[-1]):
        mark_time(ax, end, f"maneuver end {end:g} s")
    t_div = diverged_at(case, ds)
    if t_div is not None:
        mark_time(ax, t_div, "diverged", color="#D55E00")
    t_left = left_range_at(case, ds)
    if t_left is not None:
        mark_time(ax, t_left, "left the models' range", color="#D55E00")


def validity_note(case: str, ds: xr.Dataset) -> str:
    """The title's note on a flagged run, e.g. ``" [large deflection: max |v(L)| = 0.54 L]"``."""
    name = str(attr(case, ds, "validity"))
    if name == "valid":
        return ""
    ratio = float(attr(case, ds, "max_deflection_ratio"))
    return f" [{name.replace('_', ' ')}: max |v(L)| = {ratio:.2g} L]"


def plot(case: str, ds: xr.Dataset):
    """The four-panel figure of simulation ``case`` from its dataset ``ds``."""
    found = maneuver(case, ds)
    fig, axes = new_figure(4, 1, height=7.0)
    axes = axes[:, 0]
    t = times(ds)
    style = model_style(model(case, ds))
    end = maneuver_end(found)
    for index, (name, label) in enumerate(SERIES.values()):
        if name == "theta_dot" and "hub_speed" in ds:  # a compliant root: the hub's and the root's speeds
            axes[index].plot(t, variable(case, ds, "hub_speed").values, **style, label=r"hub $\dot\phi$")
            axes[index].plot(t, variable(case, ds, name).values, color="0.3", linestyle=":",
                             label=r"beam root $\dot\theta$")
            # above the panel, not over the oscillation that fills it
            axes[index].legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, fontsize=7, frameon=False,
                               borderaxespad=0.1)
            label = axis_label("speed", "rad s-1")
        else:
            axes[index].plot(t, variable(case, ds, name).values, **style)
        axes[index].set_ylabel(label)
        mark_events(axes[index], case, ds, end)
    ax = axes[3]
    energy = variable(case, ds, "energy").values
    ax.plot(t, energy - energy[0], label="$E(t) - E(0)$", **style)
    if "work" in ds.data_vars:
        net = variable(case, ds, "work").values - (
            variable(case, ds, "dissipated_energy").values if "dissipated_energy" in ds else 0.0)
        ax.plot(t, net, color="0.2", linestyle=":", label="work - dissipated")
        ax.legend(loc="best")
    ax.set_ylabel(axis_label("energy change", "J"))
    ax.set_xlabel(axis_label("time $t$", "s"))
    panel_title(axes[0], 0, f"{case}: {model(case, ds)}, n = {n_modes(case, ds)}, "
                f"{found['kind']}{validity_note(case, ds)}")
    length = float(attr(case, ds, "length"))
    limit = float(attr(case, ds, "small_deflection_limit")) * length
    peak = float(attr(case, ds, "max_deflection_ratio")) * length
    if peak > limit:  # hatch the deflections beyond the small-deflection range the run reaches
        for sign in (-1.0, 1.0):
            axes[0].axhspan(sign * limit, sign * peak, facecolor="none", hatch="//",
                            edgecolor="#D55E00", alpha=0.4, linewidth=0)
    return fig
