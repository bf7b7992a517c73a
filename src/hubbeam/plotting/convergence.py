"""Beyond the paper: convergence of the FOAM spin-up (w_f = 5 rad/s) in the number of modes.

(a) tip deflection v(L) for every mode count given; (b) its difference from the run with the most
modes; (c) peak and residual amplitude of v(L) and (d) the dominant residual frequency (least-squares
sinusoid of ``hubbeam.results.measures.fit_sinusoid`` after t_f) against the number of modes.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.plotting.figures import curve_label, mark_maneuver_end, plot_series, require_datasets
from hubbeam.plotting.style import axis_label, model_style, new_figure, panel_title
from hubbeam.results.measures import after, fit_sinusoid, peak, residual_amplitude
from hubbeam.results.reader import maneuver_value, model, n_modes, times, variable


def plot(datasets: Mapping[str, xr.Dataset]):
    require_datasets("convergence", datasets, "a run (e.g. fig06_foam_n1, n3, n5)")
    ordered = sorted(datasets.items(), key=lambda item: n_modes(*item))
    ref_case, ref = ordered[-1]
    fig, axes = new_figure(2, 2, height=4.8, width=7.0, sharex=False)
    ax = axes[0, 0]
    for variant, (case, ds) in enumerate(ordered):
        plot_series(ax, case, ds, "tip_transverse", variant=variant)
    mark_maneuver_end(ax, ref_case, ref)
    panel_title(ax, 0, f"Tip deflection, $\\omega_f$ = {maneuver_value(ref_case, ref, 'wf'):g} rad/s")
    ax.set_ylabel(axis_label("$v(L)$", "m"))
    ax.legend(loc="best")
    ax = axes[0, 1]
    for variant, (case, ds) in enumerate(ordered[:-1]):
        diff = (variable(case, ds, "tip_transverse").interp(time=ref["time"])
                - variable(ref_case, ref, "tip_transverse"))
        ax.plot(times(ref), 1e3 * diff.values, **model_style(model(case, ds), variant),
                label=curve_label(case, ds))
    mark_maneuver_end(ax, ref_case, ref)
    panel_title(ax, 1, f"Difference from {curve_label(ref_case, ref)}")
    ax.set_ylabel(axis_label("$\\Delta v(L)$", "mm"))
    # the differences oscillate over the whole run: free room above them for the legend
    low, high = ax.get_ylim()
    ax.set_ylim(low, high + 0.5 * (high - low))
    ax.legend(loc="upper left")
    for row in axes[0]:
        row.set_xlabel(axis_label("Time $t$", "s"))
    counts = np.array([n_modes(c, d) for c, d in ordered])
    ax = axes[1, 0]
    tips = [variable(c, d, "tip_transverse").values for c, d in ordered]
    ax.plot(counts, [peak(tip) for tip in tips], "o-", label="peak $|v(L)|$")
    ax.plot(counts, [residual_amplitude(times(d), tip, maneuver_value(c, d, "tf"))
                     for (c, d), tip in zip(ordered, tips)], "s--",
            label="residual amplitude ($t > t_f$)")
    panel_title(ax, 2, "Tip deflection against mode count")
    ax.set_yscale("log")
    ax.set_ylabel(axis_label("$|v(L)|$", "m"))
    ax.legend(loc="best")
    ax = axes[1, 1]
    frequencies = [residual_frequency(c, d) for c, d in ordered]
    ax.plot(counts, frequencies, "o-", label=f"{model(ref_case, ref)}, dominant residual frequency")
    panel_title(ax, 3, "Residual vibration frequency")
    ax.set_ylabel(axis_label("$f$", "Hz"))
    ax.legend(loc="best")
    for ax in axes[1]:
        ax.set_xlabel("Number of modes $n$")
        ax.set_xticks(counts)
    return fig


def residual_frequency(case: str, ds: xr.Dataset) -> float:
    """Dominant frequency (Hz) of the residual tip deflection (fitted sinusoid after t_f)."""
    tf = maneuver_value(case, ds, "tf")
    tip = variable(case, ds, "tip_transverse").values
    return fit_sinusoid(*after(times(ds), tip, tf), tf).omega / (2 * np.pi)
