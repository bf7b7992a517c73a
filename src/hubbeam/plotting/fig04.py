"""Fig. 4: tip deflection of CFOAM and FOAM for the spin-up to w_f = 3 rad/s (Eq. 43, note 1).

Panel (a) overlays the transverse tip deflection v(L) of every run; panel (b) shows each run minus
the FOAM run with the same mode count, which makes "exactly the same" measurable.
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import curve_label, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import axis_label, model_style, new_figure, panel_title
from hubbeam.results.reader import maneuver_value, model, n_modes, select, times, variable


def plot(datasets: Mapping[str, xr.Dataset]):
    require_datasets("fig04", datasets, "a CFOAM or FOAM run")
    foam = select(datasets, model="FOAM")
    others = {c: d for c, d in datasets.items() if c not in foam}
    pairs = []  # (case, dataset, FOAM reference with the same mode count)
    for case, ds in others.items():
        same_n = [ref for ref in foam.items() if n_modes(*ref) == n_modes(case, ds)]
        if same_n:
            pairs.append((case, ds, same_n[0]))
    fig, axes = new_figure(2 if pairs else 1, 1, height=4.6 if pairs else 3.0)
    ax = axes[0, 0]
    for case, ds in foam.items():
        plot_series(ax, case, ds, "tip_transverse")
    for case, ds in others.items():  # drawn on top, dashed, so coincident curves stay visible
        plot_series(ax, case, ds, "tip_transverse")
    case, ds = next(iter(datasets.items()))
    mark_maneuver_end(ax, case, ds)
    wf = maneuver_value(case, ds, "wf")
    panel_title(ax, 0, f"Transverse tip deflection, $\\omega_f$ = {wf:g} rad/s")
    ax.set_ylabel(axis_label("$v(L)$", "m"))
    ax.legend(loc="best")
    if pairs:
        ax = axes[1, 0]
        for case, ds, (ref_case, ref) in pairs:
            diff = (variable(case, ds, "tip_transverse")
                    - variable(ref_case, ref, "tip_transverse").interp(time=ds["time"]))
            ax.plot(times(ds), 1e3 * diff.values,
                    label=f"{curve_label(case, ds)} $-$ {curve_label(ref_case, ref)}",
                    **model_style(model(case, ds)))
        mark_maneuver_end(ax, case, ds)
        panel_title(ax, 1, "Difference of the tip deflections")
        ax.set_ylabel(axis_label("$\\Delta v(L)$", "mm"))
        ax.legend(loc="best")
    axes[-1, 0].set_xlabel(axis_label("Time $t$", "s"))
    return fig
