"""The command-shaping study: how well a shaper tuned on one model's linearisation predicts and
performs on the reference model (:data:`REFERENCE_MODEL`, the most complete of the four).

Every run of a study that shapes its command (``case.shaper``, :mod:`hubbeam.model.shapers`)
pairs with the unshaped run of the same final speed. Per shaped run (:func:`shaped_runs`): the
residual vibration ``max |v(L)|`` after the shaped command ends (the maneuver's end plus the
shaper's duration, :func:`hubbeam.results.measures.shaped_residual_amplitude`), its move-time
penalty (that duration), the tuning (the model and speed of the linearisation it was tuned on,
``rest`` for speed 0) and the mode it was designed for.

Two questions are kept apart (:func:`tuning_table`, :func:`shaping_verdicts`):

* **prediction**: the tuned mode's frequency against the reference model's own linear mode at
  the final speed (``reference_modes``, computed by the caller from the linear models:
  ``hubbeam.control.cases.dataset_shaping_mode``), and the residual the tuning model predicts (the
  closed form :func:`hubbeam.model.shapers.residual_vibration` of the shaper on its own design
  mode: 0 for ZV and ZVD) against the residual the reference run keeps, relative to the unshaped
  run's; the closed form on the reference mode is given beside it (what the frequency error alone
  explains);
* **performance**: the residual on the reference model against the unshaped run, against the
  same shaper tuned at rest, and against the other tunings at the same speed.

Runs with a ``frequency_ratio`` (a shaper designed at a known multiple of the reference model's
mode) give the insensitivity curve measured on the reference model (:func:`insensitivity_table`),
beside the closed form (:func:`closed_form_insensitivity`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from hubbeam.model.shapers import Shaper, multi_mode, residual_vibration
from hubbeam.reporting.products import REFERENCE_MODEL
from hubbeam.results import measures
from hubbeam.results.reader import case_config, maneuver, maneuver_end, model, shaper, times, variable

#: the tuning of a shaper tuned on the linearisation at rest (speed 0)
AT_REST = "rest"
#: the tuning models of the shapers, in the order of the tables (at rest last)
TUNINGS = ("TLAM", "SFOAM", "FOAM", "CFOAM", AT_REST)
#: the tuning model "matters" at a speed where the worst tuning leaves this many times the best's residual
MATTERS_FACTOR = 2.0
#: residuals within this relative difference of the least are tied for the least (SFOAM's and
#: FOAM's tunings differ by 1e-5 in frequency and leave residuals equal to three figures)
TIE = 0.01


def shaped_run(case: str, ds: xr.Dataset) -> dict:
    """The measures of one run (module docstring): ``case``, ``model``, ``speed`` (the maneuver's
    final speed), ``kind`` (the shaper's name, None unshaped), ``tuning`` (its model, or
    :data:`AT_REST`; None unshaped or on given frequencies), ``ratio`` (its ``frequency_ratio``,
    None without), ``design_omega``, ``design_zeta`` (its first mode), ``shaper`` (a
    :class:`~hubbeam.model.shapers.Shaper`), its design ``options`` (EI's ``v_tol``), ``penalty_s``
    and ``residual_m``."""
    found = shaper(case, ds)
    spec = case_config(case, ds).get("shaper") or {}
    recorded = maneuver(case, ds)
    speed = float(recorded["wf"] if "wf" in recorded else recorded.get("reference", {}).get("wf", math.nan))
    tip = variable(case, ds, "tip_transverse").values
    run = {"case": case, "model": model(case, ds), "speed": speed, "kind": None, "tuning": None, "ratio": None,
           "design_omega": math.nan, "design_zeta": math.nan, "shaper": None, "options": {}, "penalty_s": 0.0}
    if found is not None:
        shaped = Shaper(found["times"], found["amplitudes"], found["name"], found["modes"])
        tuned_speed = float(spec.get("speed", speed))
        tuning = None if "frequencies" in spec else (AT_REST if tuned_speed == 0.0 else spec.get("model", run["model"]))
        run |= {"kind": shaped.name, "tuning": tuning, "ratio": spec.get("frequency_ratio"),
                "design_omega": shaped.modes[0][0], "design_zeta": shaped.modes[0][1], "shaper": shaped,
                "penalty_s": shaped.duration, "options": {"v_tol": spec["v_tol"]} if "v_tol" in spec else {}}
    run["residual_m"] = measures.shaped_residual_amplitude(times(ds), tip, maneuver_end(recorded), run["penalty_s"])
    return run


def shaped_runs(datasets: Mapping[str, xr.Dataset]) -> list[dict]:
    """:func:`shaped_run` of every dataset on :data:`REFERENCE_MODEL`, each with ``unshaped_m``, the
    residual of the unshaped run at its speed (NaN when there is none), and ``relative`` (its
    residual over that one)."""
    runs = [shaped_run(case, ds) for case, ds in datasets.items() if model(case, ds) == REFERENCE_MODEL]
    unshaped = {run["speed"]: run["residual_m"] for run in runs if run["kind"] is None}
    for run in runs:
        run["unshaped_m"] = unshaped.get(run["speed"], math.nan)
        run["relative"] = run["residual_m"] / run["unshaped_m"]
    return runs


def shaping_speeds(datasets: Mapping[str, xr.Dataset]) -> list[tuple[str, float]]:
    """``(case, speed)`` of one run per final speed of the shaped runs on :data:`REFERENCE_MODEL`:
    where the caller finds the reference model's own mode (``reference_modes``)."""
    found = {}
    for run in shaped_runs(datasets):
        if run["kind"] is not None:
            found.setdefault(run["speed"], run["case"])
    return [(case, speed) for speed, case in sorted(found.items())]


def reference_modes(datasets: Mapping[str, xr.Dataset], shaping_mode) -> dict[float, tuple[float, float]]:
    """Per final speed of the shaped runs (:func:`shaping_speeds`), the ``(omega, zeta)`` of the
    mode a shaper tuned on :data:`REFERENCE_MODEL` itself would cancel: ``shaping_mode(ds, model,
    speed)`` of a run at that speed (``hubbeam.control.cases.dataset_shaping_mode``, which needs
    the linear models)."""
    found = {}
    for case, speed in shaping_speeds(datasets):
        mode = shaping_mode(datasets[case], REFERENCE_MODEL, speed)
        found[speed] = (mode.omega, mode.zeta)
    return found


def tuning_table(runs: Sequence[Mapping], reference_modes: Mapping[float, tuple[float, float]]) -> list[dict]:
    """One row per tuned shaper (no ``frequency_ratio``), sorted by kind, tuning and speed:
    ``kind``, ``tuning``, ``speed``, ``design_omega``, ``reference_omega`` (the reference model's
    mode at the speed; NaN without one), ``frequency_error`` (design over reference, minus 1),
    ``predicted`` (the tuning model's closed-form residual on its own mode, relative),
    ``explained`` (the closed form on the reference mode), ``relative`` (measured on the
    reference model, over the unshaped run's), ``residual_m``, ``unshaped_m``, ``rest_m`` (the
    same kind tuned at rest at that speed), ``penalty_s``, ``best`` (least residual of the kind's
    tunings at that speed, within :data:`TIE`)."""
    tuned = [run for run in runs if run["kind"] and run["tuning"] and run["ratio"] is None]
    rest = {(run["kind"], run["speed"]): run["residual_m"] for run in tuned if run["tuning"] == AT_REST}
    best = {}
    for run in tuned:
        key = (run["kind"], run["speed"])
        best[key] = min(best.get(key, math.inf), run["residual_m"])
    rows = []
    for run in tuned:
        omega, zeta = reference_modes.get(run["speed"], (math.nan, math.nan))
        shaped = run["shaper"]
        rows.append({
            "kind": run["kind"], "tuning": run["tuning"], "speed": run["speed"], "case": run["case"],
            "design_omega": run["design_omega"], "reference_omega": omega,
            "frequency_error": run["design_omega"] / omega - 1.0,
            "predicted": float(residual_vibration(shaped, run["design_omega"], run["design_zeta"])),
            "explained": float(residual_vibration(shaped, omega, zeta)) if math.isfinite(omega) else math.nan,
            "relative": run["relative"], "residual_m": run["residual_m"], "unshaped_m": run["unshaped_m"],
            "rest_m": rest.get((run["kind"], run["speed"]), math.nan), "penalty_s": run["penalty_s"],
            "best": run["residual_m"] <= (1.0 + TIE) * best[(run["kind"], run["speed"])]})
    order = {name: k for k, name in enumerate(TUNINGS)}
    return sorted(rows, key=lambda row: (row["kind"], order.get(row["tuning"], len(order)), row["speed"]))


def insensitivity_table(runs: Sequence[Mapping], reference_modes: Mapping[float, tuple[float, float]]) -> list[dict]:
    """One row per run with a ``frequency_ratio``, sorted by kind and ratio: ``kind``, ``speed``,
    ``ratio``, ``relative`` (measured residual over the unshaped run's), ``residual_m`` and
    ``predicted``, the closed form of the shaper on the reference model's mode at the speed."""
    rows = []
    for run in runs:
        if run["kind"] and run["ratio"] is not None:
            omega, zeta = reference_modes.get(run["speed"], (math.nan, math.nan))
            rows.append({"kind": run["kind"], "speed": run["speed"], "ratio": float(run["ratio"]), "case": run["case"],
                         "relative": run["relative"], "residual_m": run["residual_m"],
                         "predicted": float(residual_vibration(run["shaper"], omega, zeta)) if math.isfinite(omega)
                         else math.nan})
    return sorted(rows, key=lambda row: (row["kind"], row["speed"], row["ratio"]))


def closed_form_insensitivity(kind: str, omega: float, zeta: float, ratios, **options) -> np.ndarray:
    """The residual (relative to the unshaped command's) a ``kind`` shaper designed for the
    mode ``(ratio * omega, zeta)`` leaves on the mode ``(omega, zeta)``, for each of ``ratios``:
    the closed form of the curve :func:`insensitivity_table` measures (a frequency error in the
    design, the true mode fixed)."""
    return np.array([residual_vibration(multi_mode([(ratio * omega, zeta)], kind, **options), omega, zeta)
                     for ratio in np.asarray(ratios, dtype=float)])


#: a relative residual below this is a cancellation to rounding (the closed form of ZV or ZVD on its own mode)
ROUNDING = 1e-12


def _percent(values) -> str:
    return ", ".join("0" if abs(value) < ROUNDING else f"{100 * value:.2g}" for value in values) + " %"


def _speeds(rows) -> str:
    return ", ".join(f"{row['speed']:g}" for row in rows) + " rad/s"


def shaping_verdicts(table: Sequence[Mapping]) -> dict[str, dict[str, str]]:
    """Per shaper kind and tuning (``"ZV tuned on TLAM"``), two sentences with the numbers of
    :func:`tuning_table`: ``prediction`` (its mode frequency against the reference model's, the
    residual it predicts against the one the reference run keeps) and ``performance`` (the residual
    against the unshaped run, the tuning at rest and the other tunings)."""
    out = {}
    for kind, tuning in dict.fromkeys((row["kind"], row["tuning"]) for row in table):
        rows = [row for row in table if row["kind"] == kind and row["tuning"] == tuning]
        label = f"{kind} tuned {'at rest' if tuning == AT_REST else 'on ' + tuning}"
        prediction = (f"at {_speeds(rows)} its mode frequency is off by {_percent(r['frequency_error'] for r in rows)} "
                      f"from {REFERENCE_MODEL}'s; it predicts a residual of {_percent(r['predicted'] for r in rows)} "
                      f"of the unshaped run's where {REFERENCE_MODEL} keeps {_percent(r['relative'] for r in rows)} "
                      f"(the closed form on {REFERENCE_MODEL}'s mode: {_percent(r['explained'] for r in rows)})")
        best = [row for row in rows if row["best"]]
        against_rest = ("" if tuning == AT_REST else
                        f"; {', '.join(format(r['residual_m'] / r['rest_m'], '.2g') for r in rows)} times the residual "
                        "of the same shaper tuned at rest")
        performance = (f"on {REFERENCE_MODEL} it leaves {_percent(r['relative'] for r in rows)} of the unshaped "
                       f"residual{against_rest}; the least residual of the {kind} tunings "
                       + (f"at {_speeds(best)}" if best else "at no speed"))
        out[label] = {"prediction": prediction, "performance": performance}
    return out


def when_tuning_matters(table: Sequence[Mapping]) -> dict[str, str]:
    """Per shaper kind, a sentence: at which speeds the worst of the model tunings (not the one at
    rest) leaves more than :data:`MATTERS_FACTOR` times the best one's residual, and by how much."""
    out = {}
    for kind in dict.fromkeys(row["kind"] for row in table):
        spread = []
        for speed in sorted({row["speed"] for row in table if row["kind"] == kind}):
            rows = [row for row in table if row["kind"] == kind and row["speed"] == speed and row["tuning"] != AT_REST]
            if len(rows) > 1:
                best = min(rows, key=lambda row: row["residual_m"])
                worst = max(rows, key=lambda row: row["residual_m"])
                spread.append((speed, worst["residual_m"] / best["residual_m"], best["tuning"], worst["tuning"]))
        matters = [item for item in spread if item[1] > MATTERS_FACTOR]
        if not spread:
            continue
        if not matters:
            out[kind] = (f"the worst model tuning leaves at most {max(item[1] for item in spread):.2g} times the "
                         f"best one's residual at every speed ({MATTERS_FACTOR:g} times would matter)")
            continue
        out[kind] = ("the tuning model matters at " + "; ".join(
            f"{speed:g} rad/s ({worst} leaves {factor:.2g} times {best}'s residual)"
            for speed, factor, best, worst in matters)
            + (f"; elsewhere at most {max(item[1] for item in spread if item[1] <= MATTERS_FACTOR):.2g} times"
               if len(matters) < len(spread) else ""))
    return out



def shaping_dataset(runs: Sequence[Mapping], reference_modes: Mapping[float, tuple[float, float]],
                    critical_speed: float) -> xr.Dataset:
    """The study's numbers as a dataset (``report/shaping.nc``): per final speed the unshaped
    residual and the reference model's mode; per shaper kind, tuning and speed the residual, its
    share of the unshaped one, the frequency error and the move-time penalty (:func:`tuning_table`;
    NaN where not run); per kind, speed and design-frequency ratio the insensitivity measured on
    the reference model and its closed form (:func:`insensitivity_table`). TLAM's critical speed
    is an attribute."""
    table = tuning_table(runs, reference_modes)
    ratios = insensitivity_table(runs, reference_modes)
    speeds = sorted({run["speed"] for run in runs})
    kinds = list(dict.fromkeys(row["kind"] for row in table)) or ["none"]
    tunings = [name for name in TUNINGS if any(row["tuning"] == name for row in table)] or ["none"]
    grid = np.full((len(kinds), len(tunings), len(speeds)), math.nan)
    tuned = {key: grid.copy() for key in ("residual_m", "relative", "frequency_error", "penalty_s")}
    for row in table:
        at = (kinds.index(row["kind"]), tunings.index(row["tuning"]), speeds.index(row["speed"]))
        for key, values in tuned.items():
            values[at] = row[key]
    unshaped = {run["speed"]: run["residual_m"] for run in runs if run["kind"] is None}
    modes = [reference_modes.get(speed, (math.nan, math.nan)) for speed in speeds]
    r_kinds = list(dict.fromkeys(row["kind"] for row in ratios)) or ["none"]
    r_speeds = sorted({row["speed"] for row in ratios}) or [math.nan]
    r_values = sorted({row["ratio"] for row in ratios}) or [math.nan]
    measured = np.full((len(r_kinds), len(r_speeds), len(r_values)), math.nan)
    closed = measured.copy()
    for row in ratios:
        at = (r_kinds.index(row["kind"]), r_speeds.index(row["speed"]), r_values.index(row["ratio"]))
        measured[at], closed[at] = row["relative"], row["predicted"]
    tuned_dims = ("kind", "tuning", "speed")
    ratio_dims = ("insensitivity_kind", "insensitivity_speed", "ratio")
    return xr.Dataset(
        {"unshaped_residual": ("speed", [unshaped.get(speed, math.nan) for speed in speeds],
                               {"units": "m", "long_name": "max |v(L)| after the unshaped maneuver ends"}),
         "reference_omega": ("speed", [mode[0] for mode in modes],
                             {"units": "rad s-1", "long_name": f"{REFERENCE_MODEL}'s first mode the shaper excites"}),
         "reference_zeta": ("speed", [mode[1] for mode in modes], {"units": "1", "long_name": "its damping ratio"}),
         "residual": (tuned_dims, tuned["residual_m"],
                      {"units": "m", "long_name": "max |v(L)| after the shaped command ends"}),
         "relative_residual": (tuned_dims, tuned["relative"], {"units": "1", "long_name": "residual / unshaped"}),
         "frequency_error": (tuned_dims, tuned["frequency_error"],
                             {"units": "1", "long_name": f"tuned mode frequency / {REFERENCE_MODEL}'s - 1"}),
         "move_time_penalty": (tuned_dims, tuned["penalty_s"], {"units": "s", "long_name": "shaper duration"}),
         "insensitivity_measured": (ratio_dims, measured,
                                    {"units": "1", "long_name": f"residual / unshaped, measured on {REFERENCE_MODEL}"}),
         "insensitivity_closed_form": (ratio_dims, closed,
                                       {"units": "1", "long_name": "closed form for the linear mode"})},
        coords={"kind": kinds, "tuning": tunings, "speed": ("speed", speeds, {"units": "rad s-1"}),
                "insensitivity_kind": r_kinds, "insensitivity_speed": ("insensitivity_speed", r_speeds,
                                                                      {"units": "rad s-1"}),
                "ratio": ("ratio", r_values, {"long_name": "design frequency / true frequency"})},
        attrs={"title": "hubbeam command-shaping study", "reference_model": REFERENCE_MODEL,
               "tlam_critical_speed_rad_s": float(critical_speed)})
