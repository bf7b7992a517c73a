"""Fig. 8: tip deflection of FOAM and SFOAM under the torque pulse (Eq. 44), one panel per tau_max.

A panel is drawn for every torque amplitude at which at least two runs (e.g. FOAM and SFOAM with 5
and 1 modes) can be compared; FOAM solid, SFOAM dashed/dotted by mode count.
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import mark_maneuver_end, plot_series
from hubbeam.plotting.style import axis_label, new_figure, panel_title
from hubbeam.results.reader import DatasetError, distinct, model, n_modes, select


def plot(datasets: Mapping[str, xr.Dataset]):
    runs = select(datasets, kind="torque")
    taus = [tau for tau in distinct(runs, "tau_max") if len(select(runs, tau_max=tau)) >= 2]
    if not taus:
        raise DatasetError("fig08: no torque amplitude has two runs to compare "
                              f"(got {sorted(runs)}); add SFOAM cases named fig08_*")
    fig, axes = new_figure(len(taus), 1, height=2.4 * len(taus) + 0.4)
    for index, tau in enumerate(taus):
        ax = axes[index, 0]
        at_tau = select(runs, tau_max=tau)
        ordered = sorted(at_tau.items(), key=lambda item: (model(*item) != "FOAM", -n_modes(*item)))
        for variant, (case, ds) in enumerate(ordered):
            plot_series(ax, case, ds, "tip_transverse", variant=variant)
        mark_maneuver_end(ax, *ordered[0])
        panel_title(ax, index, f"$\\tau_m$ = {tau:g} N m")
        ax.set_ylabel(axis_label("$v(L)$", "m"))
        ax.legend(loc="best")
    axes[-1, 0].set_xlabel(axis_label("Time $t$", "s"))
    return fig
