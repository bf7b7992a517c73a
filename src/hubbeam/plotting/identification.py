"""Figures of a fit (``hubbeam.identification.dataset``), drawn from its dataset only.

* :func:`plot_response`: a frequency response, measured (dots) against fitted (line): magnitude,
  phase and, when measured, the coherence, on one frequency axis;
* :func:`plot_time_series`: a time series, the input and each signal measured against fitted (a
  loop's reference with the hub angle), the weighted residuals below;
* :func:`plot_modes`: a modal test, the fitted model's frequencies relative to the measured ones
  and its damping ratios, against the measured values' 95 % bars;
* :func:`plot_parameters`: every free parameter within its bounds, its fitted value with the 95 %
  interval, those not identifiable marked with the reason.

Each takes the dataset (and the experiment's name) and returns a figure; ``hubbeam.plotting.draw``
draws it in the hubbeam style and writes the PDF and PNG. A variable's role is read from its
attributes (``experiment_kind``, ``experiment_role``), never by importing the identification.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, units_tex

MEASURED = {"color": "0.25", "marker": "o", "markersize": 2.0, "linestyle": "none", "label": "measured"}
FITTED = {"color": SEQUENCE_COLORS[0], "linewidth": 1.2, "label": "fitted model"}
#: the two-sided 95 % quantile of the normal distribution (the measured bars)
Z95 = 1.959964


def _experiment(ds: xr.Dataset, name: str, kind: str) -> xr.Dataset:
    """The variables of experiment ``name``, which must be of ``kind``; a ``ValueError`` naming the
    experiments of that kind."""
    found = [var for var in ds.data_vars.values() if var.attrs.get("experiment") == name]
    if not found or found[0].attrs.get("experiment_kind") != kind:
        names = sorted({var.attrs["experiment"] for var in ds.data_vars.values()
                        if var.attrs.get("experiment_kind") == kind})
        raise ValueError(f"experiment = {name!r}; allowed: a {kind} experiment of the dataset: {', '.join(names)}")
    return ds[[var.name for var in found]]


def _role(one: xr.Dataset) -> str:
    role = next(iter(one.data_vars.values())).attrs.get("experiment_role", "")
    return "held out" if role == "held_out" else role


def plot_response(ds: xr.Dataset, experiment: str):
    """Magnitude, phase (and coherence) of the frequency response ``experiment``."""
    one = _experiment(ds, experiment, "frequency_response")
    coherence = f"{experiment}_coherence" in one
    fig, axes = new_figure(3 if coherence else 2, 1, height=5.6 if coherence else 4.4, width=5.2)
    frequency = ds[f"{experiment}_frequency"].values
    magnitude = one[f"{experiment}_magnitude_measured"]
    for label, style in (("measured", MEASURED), ("fitted", FITTED)):
        axes[0, 0].loglog(frequency, one[f"{experiment}_magnitude_{label}"], **style)
        phase = np.degrees(np.unwrap(np.radians(one[f"{experiment}_phase_{label}"].values)))
        axes[1, 0].semilogx(frequency, phase, **{**style, "label": None})
    axes[0, 0].set_ylabel(axis_label("magnitude", magnitude.attrs["units"]))
    axes[1, 0].set_ylabel(axis_label("phase", "degree").replace("degree", "deg"))
    if coherence:
        axes[2, 0].semilogx(frequency, one[f"{experiment}_coherence"], color="0.25", linewidth=0.9)
        axes[2, 0].set_ylim(0.0, 1.05)
        axes[2, 0].set_ylabel(axis_label(r"coherence $\gamma^2$", "1"))
    axes[-1, 0].set_xlabel(axis_label("frequency", "Hz"))
    axes[0, 0].legend(loc="best")
    axes[0, 0].set_title(f"{experiment} ({_role(one)}): {magnitude.attrs['long_name'].replace('measured ', '')}",
                         fontsize=8)
    return fig


def plot_time_series(ds: xr.Dataset, experiment: str):
    """The input and every signal of the time series ``experiment``, measured against fitted, and
    the weighted residuals."""
    one = _experiment(ds, experiment, "time_series")
    time = ds[f"{experiment}_time"].values
    signals = [name.removeprefix(f"{experiment}_").removesuffix("_measured") for name in one.data_vars
               if name.endswith("_measured")]
    inputs = [name for name in one.data_vars if name.removeprefix(f"{experiment}_") in ("voltage", "hub_torque")]
    rows = len(inputs) + len(signals) + 1
    fig, axes = new_figure(rows, 1, height=1.5 * rows + 0.6, width=5.6)
    row = 0
    for name in inputs:
        axes[row, 0].plot(time, one[name], color="0.25", linewidth=0.8)
        axes[row, 0].set_ylabel(axis_label(name.removeprefix(f"{experiment}_").replace("_", " "),
                                           one[name].attrs["units"]), fontsize=7)
        row += 1
    for signal in signals:
        measured = one[f"{experiment}_{signal}_measured"]
        axes[row, 0].plot(time, measured, **{**MEASURED, "marker": ".", "markersize": 1.0})
        axes[row, 0].plot(time, one[f"{experiment}_{signal}_fitted"], **FITTED)
        if signal == "hub_angle" and f"{experiment}_reference" in one:
            axes[row, 0].plot(time, one[f"{experiment}_reference"], color="0.55", linestyle="--", linewidth=0.8,
                              label="loop's reference")
        axes[row, 0].set_ylabel(axis_label(signal.replace("_", " "), measured.attrs["units"]), fontsize=7)
        row += 1
    residual = one[f"{experiment}_residual"].values
    axes[row, 0].sharex(axes[0, 0])
    per_signal = np.array_split(residual, len(signals))
    for k, (signal, values) in enumerate(zip(signals, per_signal)):
        axes[row, 0].plot(time, values, color=SEQUENCE_COLORS[(k + 1) % len(SEQUENCE_COLORS)], linewidth=0.6,
                          label=signal.replace("_", " "))
    axes[row, 0].set_ylabel(axis_label("residual / noise", "1"), fontsize=7)
    axes[row, 0].legend(loc="upper right", fontsize=6)
    axes[-1, 0].set_xlabel(axis_label("time", "s"))
    axes[len(inputs), 0].legend(loc="upper right", fontsize=6)
    axes[0, 0].set_title(f"{experiment} ({_role(one)})", fontsize=8)
    return fig


def plot_modes(ds: xr.Dataset, experiment: str):
    """The fitted model's natural frequencies (and damping ratios) of the modal test ``experiment``
    against the measured ones with their 95 % bars: the frequencies as the relative difference
    (the measured frequency in the mode's label), the damping ratios as they are."""
    one = _experiment(ds, experiment, "modal")
    damping = f"{experiment}_damping_ratio_measured" in one
    fig, axes = new_figure(1, 2 if damping else 1, height=2.9, width=6.6 if damping else 3.6, sharex=False)
    mode = ds[f"{experiment}_mode"].values
    measured = one[f"{experiment}_frequency_measured"].values
    ax = axes[0, 0]
    ax.axhline(0.0, color="0.6", linewidth=0.7)
    ax.errorbar(mode, np.zeros(mode.size), yerr=100.0 * Z95 * one[f"{experiment}_frequency_std"].values / measured,
                fmt="o", color="0.25", markersize=3, capsize=2, label="measured, 95 %")
    ax.plot(mode, 100.0 * (one[f"{experiment}_frequency_fitted"].values / measured - 1.0), "D",
            color=FITTED["color"], markersize=3.5, label="fitted model")
    ax.set_ylabel(axis_label("frequency, fitted / measured - 1", "%"), fontsize=7)
    if damping:
        ax = axes[0, 1]
        ax.errorbar(mode - 0.06, one[f"{experiment}_damping_ratio_measured"].values,
                    yerr=Z95 * one[f"{experiment}_damping_ratio_std"].values, fmt="o", color="0.25", markersize=3,
                    capsize=2)
        ax.plot(mode + 0.06, one[f"{experiment}_damping_ratio_fitted"].values, "D", color=FITTED["color"],
                markersize=3.5)
        ax.set_ylabel(axis_label("damping ratio", "1"), fontsize=7)
    for ax in axes[0]:
        ax.set_xticks(mode, [f"{k}\n{f:.4g} Hz" for k, f in zip(mode, measured)])
        ax.set_xlim(mode.min() - 0.5, mode.max() + 0.5)
        ax.set_xlabel("bending mode (measured frequency)", fontsize=7)
    axes[0, 0].legend(loc="best", fontsize=7)
    fig.suptitle(f"{experiment} ({_role(one)})", fontsize=9)
    return fig


def plot_parameters(ds: xr.Dataset):
    """Each free parameter on its own axis between its bounds: the fitted value, its 95 % interval
    and the start; a parameter that is not identifiable drawn hollow with its reason."""
    keys = [str(key) for key in ds["parameter"].values]
    fig, axes = new_figure(len(keys), 1, height=0.75 * len(keys) + 0.9, width=6.0, sharex=False)
    for ax, key in zip(axes[:, 0], keys):
        one = ds.sel(parameter=key)
        low, high = float(one["lower_bound"]), float(one["upper_bound"])
        value = float(one["value"])
        ok = bool(one["identifiable"])
        ax.axvspan(low, high, color="0.93", zorder=0)
        if np.isfinite(float(one["lower_95"])):
            ax.plot([float(one["lower_95"]), float(one["upper_95"])], [0.0, 0.0], color=FITTED["color"],
                    linewidth=3.0, solid_capstyle="butt", label="95 % interval")
        ax.plot(value, 0.0, "o", color=FITTED["color"], markerfacecolor=FITTED["color"] if ok else "white",
                markersize=6, label="fitted" if ok else "fitted, not identifiable")
        ax.plot(float(one["start_value"]), 0.0, "|", color="0.4", markersize=10, label="start")
        interval = (f", 95 %: {float(one['lower_95']):.4g} to {float(one['upper_95']):.4g}"
                    if np.isfinite(float(one["lower_95"])) else ", no interval")
        ax.annotate(f"{value:.4g}{interval}", xy=(value, 0.0), xytext=(0, -10), textcoords="offset points",
                    ha="center", va="top", fontsize=6)
        margin = 0.04 * (high - low)
        ax.set_xlim(low - margin, high + margin)
        ax.set_yticks([])
        units = str(one["parameter_units"].values)
        ax.set_ylabel(f"{key}\n({units_tex(units)})", rotation=0, ha="right", va="center", fontsize=7)
        ax.tick_params(axis="x", labelsize=7)
        if not ok:
            ax.annotate(f"not identifiable: {one['reason'].values}", xy=(0.5, 0.95), xycoords="axes fraction",
                        ha="center", va="top", fontsize=6, color="#D55E00")
    handles = {}
    for ax in axes[:, 0]:
        handles |= dict(zip(*reversed(ax.get_legend_handles_labels())))
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncols=4, fontsize=7)
    fig.suptitle(f"free parameters of case {ds.attrs.get('case', '')} within their bounds (grey)", fontsize=9)
    return fig


__all__ = ["plot_modes", "plot_parameters", "plot_response", "plot_time_series"]
