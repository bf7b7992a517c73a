"""Figures of the validation, drawn from the result datasets only, in the project's style.

* :func:`exudyn_comparison` -- one row per validation case: (left) the tip deflection of the
  Exudyn reference and of every model, (right) the absolute difference model minus reference on a
  logarithmic scale, so that FOAM's 1e-5 m and a diverging TLAM fit one axis.
* :func:`rotating_frequencies` -- the dimensionless first frequencies against the speed ratio with
  the published values as markers.
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np
import pandas as pd
import xarray as xr

from hubbeam.plotting.style import axis_label, mark_time, model_style, new_figure
from hubbeam.validation import published
from hubbeam.validation.comparison import REFERENCE

REFERENCE_STYLE = {"color": "0.1", "linestyle": "-", "linewidth": 2.4, "alpha": 0.35}


def exudyn_comparison(datasets: Mapping[str, xr.Dataset]):
    """The comparison figure of :func:`hubbeam.validation.comparison.comparison_dataset` data."""
    if not datasets:
        raise ValueError("exudyn_comparison: no validation case given; allowed: one dataset or more")
    fig, axes = new_figure(len(datasets), 2, height=2.3 * len(datasets) + 0.6, width=7.2,
                           sharex=True)
    for row, ds in enumerate(datasets.values()):
        config = json.loads(ds.attrs["case_config"])
        tip = config.get("tip_mass") or {"mass": 0.0}
        time = ds["time"].values
        reference = ds["tip_transverse_reference"].values
        left, right = axes[row]
        left.plot(time, reference, label=REFERENCE, **REFERENCE_STYLE)
        for model in ds["model"].values:
            run = ds.sel(model=model)
            style = model_style(str(model))
            left.plot(time, run["tip_transverse"].values, label=str(model), linewidth=1.0, **style)
            right.semilogy(time, np.abs(run["difference"].values), label=str(model),
                           linewidth=0.9, **style)
            if int(run["diverged"]):
                mark_time(left, float(run["diverged_at_s"]), f"{model} diverged")
        bound = 1.4 * np.max(np.abs(reference))
        left.set_ylim(-bound, bound)
        right.set_ylim(1e-8, 10.0)
        title = (f"$\\omega_f$ = {config['maneuver']['wf']:g} rad/s"
                 + (f", $m_t$ = {tip['mass']:g} kg" if tip["mass"] else ""))
        left.set_title(f"({chr(ord('a') + 2 * row)}) tip deflection, {title}")
        right.set_title(f"({chr(ord('a') + 2 * row + 1)}) |model $-$ {REFERENCE}| (same case)")
        left.set_ylabel(axis_label("$v(L)$", "m"))
        right.set_ylabel(axis_label("$|\\Delta v(L)|$", "m"))
        tf = float(config["maneuver"]["tf"])
        mark_time(left, tf, f"$t_f$ = {tf:g} s")
        right.axvline(tf, color="0.55", linewidth=0.7, linestyle=":", zorder=0)
    # one legend for every panel, above them, clear of the curves
    fig.legend(*axes[0][0].get_legend_handles_labels(), loc="outside upper center",
               ncols=1 + len(datasets[next(iter(datasets))]["model"]))
    for ax in axes[-1]:
        ax.set_xlabel(axis_label("Time $t$", "s"))
    return fig


def rotating_frequencies(curves: xr.Dataset, table: pd.DataFrame):
    """First frequencies against ``gamma`` with the published values (:mod:`rotating_eigen`)."""
    fig, axes = new_figure(1, 2, height=3.2, width=7.2, sharex=False)
    overview, zoom = axes[0]
    gamma = curves["gamma"].values
    lines = {"flapwise": ("#0072B2", "-"), "chordwise": ("#D55E00", "-"),
             "chordwise_uncoupled": ("#D55E00", ":")}
    for ax in (overview, zoom):
        for direction, (color, linestyle) in lines.items():
            ax.plot(gamma, curves[f"omega_{direction}"].values, color=color, linestyle=linestyle,
                    linewidth=1.0, label=direction.replace("_", ", ").replace(
                        "uncoupled", "no axial coupling"))
        for (source, direction), rows in table.groupby(["source", "direction"]):
            marker = "o" if source.startswith("hamza") else "s"
            ax.plot(rows["gamma"], rows["published"], linestyle="none", marker=marker,
                    markersize=4, markerfacecolor="none", color=lines[direction][0],
                    label=f"{direction}, {published.short_name(source)}")
    zoom.set_xlim(0.0, 12.5)
    zoom.set_ylim(3.0, 14.0)
    overview.set_title(f"(a) $\\alpha$ = {curves.attrs['alpha']:g}, $\\delta$ = "
                       f"{curves.attrs['delta']:g}, {curves.attrs['n_modes']} modes")
    zoom.set_title("(b) detail, $\\gamma \\leq$ 12")
    for ax in (overview, zoom):
        ax.set_xlabel(axis_label("Speed ratio $\\gamma$", "1"))
        ax.set_ylabel(axis_label("First frequency $\\bar\\omega_1$", "1"))
    fig.legend(*zoom.get_legend_handles_labels(), loc="outside lower center", ncols=2)
    return fig
