"""Fig. 10: TLAM with a tip mass at the beam tip, spin-up to w_f = 2 rad/s (note 12).

One panel per tip mass (0, 0.1, 0.5 kg), each with TLAM and, for reference, FOAM. Diverged runs
are drawn up to divergence and marked.
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import limit_to_bounded, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import axis_label, new_figure, panel_title
from hubbeam.results.reader import distinct, maneuver_value, model, select, tip_position


def plot(datasets: Mapping[str, xr.Dataset]):
    require_datasets("fig10", datasets, "a TLAM run with a tip mass")
    masses = distinct(datasets, "tip_mass")
    fig, axes = new_figure(len(masses), 1, height=2.0 * len(masses) + 0.6)
    for index, mass in enumerate(masses):
        ax = axes[index, 0]
        with_mass = select(datasets, tip_mass=mass)
        ordered = sorted(with_mass.items(), key=lambda item: model(*item) != "TLAM")
        for case, ds in ordered:
            plot_series(ax, case, ds, "tip_transverse")
        limit_to_bounded(ax, with_mass, "tip_transverse")
        case, ds = ordered[0]
        mark_maneuver_end(ax, case, ds)
        what = f"$m_t$ = {mass:g} kg at $l$ = {tip_position(case, ds):g} m" if mass > 0 else "no tip mass"
        panel_title(ax, index, f"{what}, "
                               f"$\\omega_f$ = {maneuver_value(case, ds, 'wf'):g} rad/s")
        ax.set_ylabel(axis_label("$v(L)$", "m"))
        ax.legend(loc="best")
    axes[-1, 0].set_xlabel(axis_label("Time $t$", "s"))
    return fig
