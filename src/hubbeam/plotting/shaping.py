"""The figures of a command-shaping study (:mod:`hubbeam.study.shaping`), drawn from its runs.

:func:`residuals`: the residual vibration after the shaped command ends against the final speed,
one panel per shaper kind, one line per tuning (the model whose linearisation it was tuned on at
the final speed, or at rest) and the unshaped runs, log axis; TLAM's critical speed for the
runs' beam and tip mass is marked (TLAM has no mode to tune on beyond it).
:func:`insensitivity_zv`, :func:`insensitivity_zvd`, :func:`insensitivity_ei`: the residual
relative to the unshaped run's against the design frequency over the reference model's mode,
measured on the reference model (markers) and the closed form of the linear mode (line).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.control.cases import dataset_critical_speed, dataset_shaping_mode
from hubbeam.plotting.style import SEQUENCE_COLORS, axis_label, new_figure, panel_title
from hubbeam.study.shaping import (
    AT_REST,
    REFERENCE_MODEL,
    TUNINGS,
    closed_form_insensitivity,
    reference_modes,
    shaped_runs,
)

#: the ratios of the closed-form curve of an insensitivity figure, beyond the measured ones
CURVE_POINTS = 161
#: line, marker, marker size and fill per tuning: SFOAM's and FOAM's modes nearly coincide, so
#: their lines must stay apart to the eye (hollow triangles over small dots)
TUNING_STYLE = {"TLAM": ("-", "s", 4, "full"), "SFOAM": ("-", "^", 8, "none"), "FOAM": (":", "o", 3, "full"),
                "CFOAM": ("-.", "d", 5, "none"), AT_REST: ("--", "s", 5, "none")}


def _tuning_label(tuning: str) -> str:
    return "tuned at rest" if tuning == AT_REST else f"tuned on {tuning}"


def residuals(name: str, datasets: Mapping[str, xr.Dataset]):
    """Residual vibration against final speed per shaper kind and tuning (module docstring)."""
    runs = shaped_runs(datasets)
    tuned = [run for run in runs if run["kind"] and run["tuning"] and run["ratio"] is None]
    kinds = list(dict.fromkeys(run["kind"] for run in tuned))
    unshaped = sorted((run["speed"], run["residual_m"]) for run in runs if run["kind"] is None)
    critical = dataset_critical_speed(datasets[runs[0]["case"]], "TLAM")
    fig, axes = new_figure(len(kinds), 1, height=3.2 * len(kinds))
    for k, (ax, kind) in enumerate(zip(axes[:, 0], kinds)):
        ax.semilogy(*zip(*unshaped), "-o", color="0.2", markersize=4, label="unshaped")
        for j, tuning in enumerate(t for t in TUNINGS if any(run["tuning"] == t for run in tuned)):
            points = sorted((run["speed"], run["residual_m"]) for run in tuned
                            if run["kind"] == kind and run["tuning"] == tuning)
            if points:
                line, marker, size, fill = TUNING_STYLE[tuning]
                ax.semilogy(*zip(*points), linestyle=line, marker=marker, markersize=size, fillstyle=fill,
                            color=SEQUENCE_COLORS[j % len(SEQUENCE_COLORS)], label=_tuning_label(tuning))
        if math.isfinite(critical):
            ax.axvline(critical, color="0.5", linestyle=":", linewidth=1.0)
            ax.annotate(f"TLAM critical speed {critical:.3g} rad/s", (critical, 1.0),
                        xycoords=("data", "axes fraction"), xytext=(-3, -3), textcoords="offset points",
                        rotation=90, ha="right", va="top", fontsize=6)
        ax.set_ylabel(axis_label(r"residual $|v(L)|$", "m"))
        panel_title(ax, k, f"{kind} shaper, run on {REFERENCE_MODEL}")
        ax.legend(loc="lower right", fontsize=6)
    axes[-1, 0].set_xlabel(axis_label(r"final speed $\omega_f$", "rad s$^{-1}$"))
    return fig


def insensitivity(kind: str, name: str, datasets: Mapping[str, xr.Dataset]):
    """The insensitivity curve of the ``kind`` shaper (module docstring), one line per speed."""
    runs = [run for run in shaped_runs(datasets) if run["kind"] == kind and run["ratio"] is not None]
    speeds = sorted({run["speed"] for run in runs})
    modes = reference_modes(datasets, dataset_shaping_mode)
    fig, axes = new_figure(1, 1)
    ax = axes[0, 0]
    ratios = [run["ratio"] for run in runs]
    dense = np.linspace(min(ratios + [0.6]), max(ratios + [1.4]), CURVE_POINTS)
    for j, speed in enumerate(speeds):
        color = SEQUENCE_COLORS[j % len(SEQUENCE_COLORS)]
        omega, zeta = modes[speed]
        measured = sorted((run["ratio"], run["relative"]) for run in runs if run["speed"] == speed)
        options = next(run["options"] for run in runs if run["speed"] == speed)
        ax.plot(dense, 100 * closed_form_insensitivity(kind, omega, zeta, dense, **options), "-", color=color,
                label=rf"closed form, linear mode $\omega$ = {omega:.4g} rad/s, $\zeta$ = {zeta:.2g}")
        ax.plot(*zip(*[(ratio, 100 * value) for ratio, value in measured]), "o", color=color, markersize=5,
                label=rf"measured on {REFERENCE_MODEL}, $\omega_f$ = {speed:g} rad/s")
    ax.axvline(1.0, color="0.6", linewidth=0.8)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("design frequency / true frequency")
    ax.set_ylabel("residual / unshaped residual (%)")
    panel_title(ax, 0, f"{kind} shaper's insensitivity ({name})")
    ax.legend(loc="upper center", fontsize=6)
    return fig


insensitivity_zv = functools.partial(insensitivity, "ZV")
insensitivity_zvd = functools.partial(insensitivity, "ZVD")
insensitivity_ei = functools.partial(insensitivity, "EI")
