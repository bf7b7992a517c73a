"""Fig. 7: the inertia torque Q_theta (Eq. 32) under the torque pulse of Eq. 44 (note 8), FOAM.

(a) Q_theta(t) for the largest tau_max given (the paper: 400 N m); (b) Q_theta / tau_max in percent
for every torque amplitude, the quantity behind Table 3 and reproduction note 9.
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import curve_label, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, panel_title
from hubbeam.results.reader import distinct, model, select


def plot(datasets: Mapping[str, xr.Dataset]):
    # SFOAM deletes Q_theta (Eq. 40), so only the other models are drawn.
    runs = {c: d for c, d in select(datasets, kind="torque").items() if model(c, d) != "SFOAM"}
    require_datasets("fig07", runs, "a FOAM torque-pulse run")
    taus = distinct(runs, "tau_max")
    fig, axes = new_figure(2, 1, height=5.0)
    ax = axes[0, 0]
    largest = select(runs, tau_max=taus[-1])
    for case, ds in largest.items():
        plot_series(ax, case, ds, "Q_theta")
    mark_maneuver_end(ax, *next(iter(largest.items())))
    panel_title(ax, 0, f"Inertia torque $Q_\\theta$, $\\tau_m$ = {taus[-1]:g} N m")
    ax.set_ylabel(axis_label("$Q_\\theta$", "N m"))
    ax.legend(loc="best")
    ax = axes[1, 0]
    for variant, tau in enumerate(taus):
        for case, ds in select(runs, tau_max=tau).items():
            plot_series(ax, case, ds, "Q_theta", scale=100.0 / tau,
                        color=SEQUENCE_COLORS[variant % len(SEQUENCE_COLORS)],
                        label=f"{curve_label(case, ds)}, $\\tau_m$ = {tau:g} N m")
    mark_maneuver_end(ax, *next(iter(runs.items())))
    panel_title(ax, 1, "Inertia torque relative to the torque amplitude")
    ax.set_ylabel(axis_label("$Q_\\theta / \\tau_m$", "%"))
    ax.set_xlabel(axis_label("Time $t$", "s"))
    ax.legend(loc="best")
    return fig
