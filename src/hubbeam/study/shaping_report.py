"""The section of a command-shaping study in the study report (:mod:`hubbeam.study.shaping`):
its tables in Markdown and its verdicts, as the template ``study_report.md.j2`` shows them."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import number
from hubbeam.study.shaping import (
    REFERENCE_MODEL,
    ROUNDING,
    insensitivity_table,
    shaping_verdicts,
    tuning_table,
    when_tuning_matters,
)


def _pct(value: float) -> str:
    return "0" if abs(value) < ROUNDING else number(100 * value, 3)


def shaping_section(runs: Sequence[Mapping], reference_modes: Mapping[float, tuple[float, float]],
                    critical_speed: float) -> dict:
    """What the study report shows of a shaping study (``reporting/templates/study_report.md.j2``):
    the unshaped runs and the reference model's mode per speed, the tuned shapers
    (:func:`tuning_table`) and the insensitivity runs (:func:`insensitivity_table`) as Markdown
    tables, the verdicts (:func:`shaping_verdicts`, :func:`when_tuning_matters`) and TLAM's
    ``critical_speed`` (rad s-1) for the runs' beam."""
    table = tuning_table(runs, reference_modes)
    ratios = insensitivity_table(runs, reference_modes)
    unshaped = sorted((run["speed"], run["residual_m"]) for run in runs if run["kind"] is None)
    baseline = markdown_table(
        ("final speed (rad/s)", "unshaped residual (m)", f"{REFERENCE_MODEL} mode (rad/s)", "damping ratio"),
        ([number(speed), number(residual, 3), number(reference_modes.get(speed, (math.nan,))[0], 4),
          number(reference_modes.get(speed, (math.nan, math.nan))[1], 3)] for speed, residual in unshaped))
    tuned = markdown_table(
        ("shaper", "tuned on", "final speed (rad/s)", "tuned mode (rad/s)", "frequency error (%)",
         "predicted residual (%)", f"closed form on {REFERENCE_MODEL}'s mode (%)", f"{REFERENCE_MODEL} residual (m)",
         "of unshaped (%)", "of tuned at rest", "move-time penalty (s)"),
        ([row["kind"], row["tuning"], number(row["speed"]), number(row["design_omega"], 4),
          _pct(row["frequency_error"]), _pct(row["predicted"]), _pct(row["explained"]), number(row["residual_m"], 3),
          _pct(row["relative"]), number(row["residual_m"] / row["rest_m"], 3), number(row["penalty_s"], 3)]
         for row in table))
    insensitivity = markdown_table(
        ("shaper", "final speed (rad/s)", "design / true frequency", f"{REFERENCE_MODEL} residual (m)",
         "of unshaped (%)", "closed form (%)"),
        ([row["kind"], number(row["speed"]), number(row["ratio"]), number(row["residual_m"], 3),
          _pct(row["relative"]), _pct(row["predicted"])] for row in ratios)) if ratios else ""
    return {"reference_model": REFERENCE_MODEL, "critical_speed": critical_speed, "baseline_table": baseline,
            "tuning_table": tuned, "insensitivity_table": insensitivity, "verdicts": shaping_verdicts(table),
            "matters": when_tuning_matters(table)}
