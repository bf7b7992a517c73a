"""Fig. 6: FOAM spin-up to w_f = 5 rad/s, t_f = 30 s.

(a) the transverse modal coordinates q2_i of the run with the most modes; the modes are normalised
to unit modal mass of the bare beam (reproduction note 7), so q2_i is in kg^1/2 m.
(b) the pure axial tip deformation w1(L) for every mode count given (n = 1, 3, 5).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.plotting.figures import curve_label, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, number_tex, panel_title
from hubbeam.results.reader import maneuver_value, n_modes, times, units, variable


def plot(datasets: Mapping[str, xr.Dataset]):
    require_datasets("fig06", datasets, "a FOAM spin-up run")
    case, ds = max(datasets.items(), key=lambda item: n_modes(*item))
    q2 = variable(case, ds, "q2")
    fig, axes = new_figure(2, 1, height=5.0)
    ax = axes[0, 0]
    for k, mode in enumerate(q2["mode"].values):
        series = q2.sel(mode=mode).values
        peak = float(np.nanmax(np.abs(series)))
        ax.plot(times(ds), series, color=SEQUENCE_COLORS[k % len(SEQUENCE_COLORS)],
                label=f"$q_{{2,{int(mode)}}}$ (max |q| = {number_tex(peak)})")
    mark_maneuver_end(ax, case, ds)
    wf = maneuver_value(case, ds, "wf")
    panel_title(ax, 0, f"Modal responses, {curve_label(case, ds)}, $\\omega_f$ = {wf:g} rad/s "
                       "(unit modal mass normalisation)")
    ax.set_ylabel(axis_label("$q_{2,i}$", units(case, ds, "q2")))
    ax.legend(loc="lower right")  # after t_f every coordinate is near zero: free space
    ax = axes[1, 0]
    ordered = sorted(datasets.items(), key=lambda item: n_modes(*item))
    for variant, (c, d) in enumerate(ordered):
        plot_series(ax, c, d, "tip_axial", variant=variant)
    mark_maneuver_end(ax, case, ds)
    panel_title(ax, 1, "Axial tip deformation $w_1(L)$ for different numbers of modes")
    ax.set_ylabel(axis_label("$w_1(L)$", "m"))
    ax.set_xlabel(axis_label("Time $t$", "s"))
    ax.legend(loc="best")
    return fig
