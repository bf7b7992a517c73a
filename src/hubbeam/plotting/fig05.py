"""Fig. 5: TLAM against FOAM below (2.8 rad/s) and above (3.5 rad/s) TLAM's critical speed.

Rows: transverse tip deflection v(L) = f2(L) q2, pure axial tip deformation w1(L) = f1(L) q1
(reproduction note 11: not w1 + wc). One column per final speed w_f; panels are labelled row by
row, (a), (b) transverse, (c), (d) axial for two speeds. A diverged run is drawn up to its
divergence time, marked, and allowed to leave the frame so the bounded runs stay readable.
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import limit_to_bounded, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import axis_label, new_figure, panel_title
from hubbeam.results.reader import distinct, select

ROWS = (
    ("tip_transverse", "Transverse tip deflection", "$v(L)$"),
    ("tip_axial", "Axial tip deformation", "$w_1(L)$"),
)


def plot(datasets: Mapping[str, xr.Dataset]):
    require_datasets("fig05", datasets, "a TLAM or FOAM spin-up run")
    speeds = distinct(datasets, "wf")
    fig, axes = new_figure(len(ROWS), len(speeds), height=4.8, width=3.4 * len(speeds) + 0.4,
                           sharex="col")
    for col, wf in enumerate(speeds):
        at_speed = select(datasets, wf=wf)
        for row, (name, what, symbol) in enumerate(ROWS):
            ax = axes[row, col]
            for case, ds in at_speed.items():
                plot_series(ax, case, ds, name)
            limit_to_bounded(ax, at_speed, name)
            mark_maneuver_end(ax, *next(iter(at_speed.items())))
            panel_title(ax, row * len(speeds) + col, f"{what}, $\\omega_f$ = {wf:g} rad/s")
            ax.set_ylabel(axis_label(symbol, "m"))
            ax.legend(loc="lower left")
        axes[-1, col].set_xlabel(axis_label("Time $t$", "s"))
    return fig
