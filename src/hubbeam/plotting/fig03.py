"""Fig. 3: the CFOAM high-order contributions along the CFOAM trajectory (w_f = 3 rad/s, 1 mode).

Each panel shows one difference CFOAM minus FOAM evaluated on the CFOAM trajectory
(reproduction note 5): the rotary inertia ``dM_thth`` (the Delta term of Eq. 25), the
generalised force of the theta equation ``dQ_theta`` (Eqs. 32, 37, with the acceleration terms of
the mass-matrix difference moved to the right-hand side) and the generalised forces of the axial and
transverse equations ``dQ_q1``, ``dQ_q2`` (Eqs. 33-34, 38-39).
"""

from __future__ import annotations

from collections.abc import Mapping

import xarray as xr

from hubbeam.plotting.figures import curve_label, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import VARIANT_LINESTYLES as LINESTYLES
from hubbeam.plotting.style import axis_label, new_figure, panel_title, symbol_tex
from hubbeam.results.reader import maneuver_value, select, units, variable

#: (variable, what the panel shows)
PANELS = (
    ("dM_thth", "rotary inertia $M_{\\theta\\theta}$"),
    ("dQ_theta", "generalised force of the $\\theta$ equation"),
    ("dQ_q1", "axial generalised force $Q_{q_1}$"),
    ("dQ_q2", "transverse generalised force $Q_{q_2}$"),
)


def plot(datasets: Mapping[str, xr.Dataset]):
    """Four panels, one per high-order contribution, for every CFOAM dataset given."""
    cfoam = select(datasets, model="CFOAM")
    require_datasets("fig03", cfoam, "a CFOAM run carrying dM_thth, dQ_theta, dQ_q1, dQ_q2")
    for case, ds in cfoam.items():  # fail before drawing anything, naming the missing variable
        for name, _ in PANELS:
            variable(case, ds, name)
    fig, axes = new_figure(2, 2, height=4.6, width=7.0)
    for index, (ax, (name, what)) in enumerate(zip(axes.flat, PANELS)):
        for variant, (case, ds) in enumerate(cfoam.items()):
            da = variable(case, ds, name)
            if "mode" in da.dims:
                for k, mode in enumerate(da["mode"].values):
                    dashes = LINESTYLES[(variant + k) % len(LINESTYLES)]
                    plot_series(ax, case, ds, name, mode=int(mode), linestyle=dashes,
                                label=f"{curve_label(case, ds)}, mode {int(mode)}")
            else:
                plot_series(ax, case, ds, name, linestyle=LINESTYLES[variant % len(LINESTYLES)])
        case, ds = next(iter(cfoam.items()))
        mark_maneuver_end(ax, case, ds)
        panel_title(ax, index, what)
        ax.set_ylabel(axis_label(symbol_tex(name), units(case, ds, name)))
        ax.legend(loc="best")
    for ax in axes[-1]:
        ax.set_xlabel(axis_label("Time $t$", "s"))
    wf = {maneuver_value(c, d, "wf") for c, d in cfoam.items()}
    fig.suptitle("High-order contributions (CFOAM minus FOAM) along the CFOAM trajectory, "
                 + ", ".join(f"$\\omega_f$ = {w:g} rad/s" for w in sorted(wf)), fontsize=9)
    return fig
