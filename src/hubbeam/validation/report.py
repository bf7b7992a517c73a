"""The validation parts of the reports, written from the validation result files only.

* :func:`published_section` -- the "Validation" section of the reproduction report: the
  constant-speed linearisation of FOAM against the published first frequencies of rotating
  cantilevers (Wright et al. 1982; Hodges and Rutkowski 1981; Hamza-Cherif and Houmat 2004) and
  the tip-mass frequency equation, from the files of rule ``validate_published``
  (``published_comparison.csv``, ``tip_mass_comparison.csv``, ``rotating_eigen.nc`` and the figure).
* :func:`exudyn_markdown` -- the report of the comparison with the Exudyn ANCF reference
  (``results/report/validation_exudyn.md``), from the files of ``snakemake validate``
  (``exudyn_comparison.csv``, ``exudyn_mode_study.csv``, ``exudyn_convergence.csv``, the figure).

Every number of the text (counts, ratios, the evidence for how a table's last digit was
obtained, the key findings of docs/validation.md) is computed here from those files; none is
typed in. A missing file raises :class:`hubbeam.io.ResultFileError` naming it and the command
that builds it; a file without a needed column raises :class:`ValidationInputError`.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Sequence
from decimal import ROUND_DOWN, ROUND_HALF_EVEN, Decimal
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd

from hubbeam import __version__
from hubbeam.io import ResultFileError, open_result
from hubbeam.validation import published
from hubbeam.validation.rotating_eigen import allowed_interval

READINGS = ("rounded", "truncated")

PUBLISHED_COLUMNS = ("source", "direction", "gamma", "alpha", "printed", "published", "rounding",
                     "modal_change", "difference", "allowed_low", "allowed_high", "agrees")
TIP_MASS_COLUMNS = ("mu", "printed", "published", "modal_change", "difference", "allowed_low",
                    "allowed_high", "agrees")
COMPARISON_COLUMNS = ("case", "model", "wf", "tf", "tip_mass_kg", "n_modes", "max_abs_difference_m",
                      "max_abs_difference_rel_peak", "peak_m", "peak_reference_m", "residual_m",
                      "residual_reference_m", "residual_ratio", "diverged", "diverged_at_s")
MODE_STUDY_COLUMNS = ("case", "model", "n_modes", "max_abs_difference_m")
CONVERGENCE_COLUMNS = ("study", "value", "elements", "time_step_s", "newton_tolerance", "production",
                       "max_abs_difference_to_finest_m", "max_abs_difference_to_next_finer_m",
                       "newton_iterations", "cpu_time_s")

#: how each validation file is built (for the error naming a missing one)
BUILD_PUBLISHED = "`snakemake {path}` (rule validate_published, part of `snakemake`)"
BUILD_EXUDYN = "`snakemake validate` (needs the Exudyn extra: `pip install -e .[validation]`)"

#: sources of the Exudyn reference (docs/validation.md)
EXUDYN_SOURCES = (
    "J. Gerstmayr: Exudyn - a C++-based Python package for flexible multibody systems. Multibody "
    "System Dynamics 60 (2024) 533-561.",
    "J. Gerstmayr, H. Irschik: On the correct representation of bending and axial deformation in "
    "the absolute nodal coordinate formulation with an elastic line approach. Journal of Sound and "
    "Vibration 318 (2008) 461-487.",
    "J. Chung, G. M. Hulbert: A time integration algorithm for structural dynamics with improved "
    "numerical dissipation: the generalized-alpha method. Journal of Applied Mechanics 60 (1993) "
    "371-375.",
    "M. Arnold, O. Brüls: Convergence of the generalized-alpha scheme for constrained mechanical "
    "systems. Multibody System Dynamics 18 (2007) 185-202.",
)


class ValidationInputError(ValueError):
    """A validation result file lacks what the report needs (names the file and the column)."""


class Section(NamedTuple):
    """A report section and the one sentence the report's summary gives it."""

    summary: str
    markdown: str


# --- reading --------------------------------------------------------------------------------------

def read_result_table(path, columns: Sequence[str], build: str) -> pd.DataFrame:
    """The csv ``path`` with at least ``columns`` and one row (``printed`` kept as text, so that
    its trailing zeros, the printed precision, survive). ``build`` says how to make the file."""
    path = Path(path)
    if not path.is_file():
        raise ResultFileError(f"validation result {path} does not exist; build it with "
                              f"{build.format(path=path)}")
    table = pd.read_csv(path, dtype={"printed": str})
    missing = [column for column in columns if column not in table.columns]
    if missing:
        raise ValidationInputError(f"{path}: missing column(s) {', '.join(missing)}; "
                                   f"has: {', '.join(table.columns)}")
    if table.empty:
        raise ValidationInputError(f"{path}: no rows")
    return table


def _mode_columns(table: pd.DataFrame, prefix: str, path) -> list[tuple[int, str]]:
    """``[(n, "<prefix><n>"), ...]`` of the per-mode-count columns, ascending in ``n``."""
    found = sorted((int(match.group(1)), column) for column in table.columns
                   if (match := re.fullmatch(re.escape(prefix) + r"(\d+)", column)))
    if not found:
        raise ValidationInputError(f"{path}: no column {prefix}<modes> (our values per mode count)")
    return found


def _link(path, report_dir) -> str:
    return Path(os.path.relpath(Path(path).resolve(), Path(report_dir).resolve())).as_posix()


# --- formatting -----------------------------------------------------------------------------------

def _g(value, digits: int = 3) -> str:
    """``value`` to ``digits`` significant figures, '-' for NaN."""
    value = float(value)
    return "-" if math.isnan(value) else f"{value:.{digits}g}"


def _percent(fraction: float) -> str:
    """``0.00045`` -> ``"0.045 %"``, ``2.07`` -> ``"207 %"`` (two significant figures below 10 %)."""
    value = 100.0 * float(fraction)
    return f"{value:.0f} %" if abs(value) >= 10.0 else f"{value:.2g} %"


def _range(values, digits: int = 2, scale: float = 1.0, unit: str = "") -> str:
    """``"a to b"`` (or ``"a"`` when equal at the shown precision) of ``values * scale``."""
    low, high = (f"{scale * float(v):.{digits}g}" for v in (np.min(values), np.max(values)))
    return f"{low}{unit}" if low == high else f"{low}{unit} to {high}{unit}"


def _case_label(row) -> str:
    label = f"w_f = {row['wf']:g} rad/s"
    return label + (f", m_t = {row['tip_mass_kg']:g} kg" if row["tip_mass_kg"] else "")


def _quantize(value: float, printed: str, rounding: str) -> Decimal:
    """``value`` to the decimal places of ``printed`` (``ROUND_DOWN`` chops; values are > 0)."""
    return Decimal(repr(float(value))).quantize(Decimal(printed), rounding=rounding)


# --- the published tables -------------------------------------------------------------------------

def reading_agreement(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with ``agrees_rounded`` and ``agrees_truncated``: would each row agree if the
    source's last printed digit were rounded, or truncated (same widening by ``modal_change``)?"""
    table = table.copy()
    for reading in READINGS:
        bounds = [allowed_interval(printed, reading, change)
                  for printed, change in zip(table["printed"], table["modal_change"])]
        table[f"agrees_{reading}"] = [low <= diff <= high
                                      for (low, high), diff in zip(bounds, table["difference"])]
    return table


def _resolved(row) -> bool:
    """Our value is converged well below the printed precision (truncation estimate < u/2)."""
    return row["modal_change"] < 0.5 * published.printed_unit(row["printed"])


def _reading_evidence(table: pd.DataFrame, ours: str) -> list[str]:
    """Bullets: per source, how many entries agree under each reading, and what decides it."""
    table = reading_agreement(table)
    bullets = []
    for source, rows in table.groupby("source", sort=False):
        count = len(rows)
        taken = rows["rounding"].iloc[0]
        text = (f"{published.short_name(source)}: read as rounded {int(rows['agrees_rounded'].sum())} "
                f"of {count} agree, read as truncated {int(rows['agrees_truncated'].sum())} of "
                f"{count}; taken as **{taken}**.")
        misses = rows[~rows["agrees_rounded"]]
        if taken == "truncated" and len(misses):
            listed = "; ".join(f"{row['direction']} gamma = {row['gamma']:g}: ours {row[ours]:.6f}, "
                               f"printed {row['printed']}" for _, row in misses.iterrows())
            below = bool((misses["difference"] > 0).all())
            text += (f" Read as rounded, the misses are {listed}"
                     + (", each printed value lying below ours, as chopping gives." if below else "."))
        resolved = rows[rows.apply(_resolved, axis=1)]
        if len(resolved):
            chopped = sum(_quantize(row[ours], row["printed"], ROUND_DOWN) == Decimal(row["printed"])
                          for _, row in resolved.iterrows())
            rounded = sum(_quantize(row[ours], row["printed"], ROUND_HALF_EVEN) == Decimal(row["printed"])
                          for _, row in resolved.iterrows())
            text += (f" Of the {len(resolved)} entries our basis resolves below half a printed unit, "
                     f"rounding our value to the printed decimals reproduces {rounded}, chopping it "
                     f"reproduces {chopped}.")
        bullets.append(text)
    for (direction, gamma), rows in table.groupby(["direction", "gamma"]):
        if rows["source"].nunique() > 1 and rows["printed"].nunique() > 1:
            value = rows[ours].iloc[0]
            printed = ", ".join(f"{row['printed']} ({published.short_name(row['source'])})"
                                for _, row in rows.iterrows())
            rounded = {str(_quantize(value, p, ROUND_HALF_EVEN)) for p in rows["printed"]}
            chopped = {str(_quantize(value, p, ROUND_DOWN)) for p in rows["printed"]}
            bullets.append(f"The same {direction} frequency at gamma = {gamma:g} is printed as "
                           f"{printed}. Ours, {value:.6f}, rounds to {', '.join(sorted(rounded))} "
                           f"and chops to {', '.join(sorted(chopped))}.")
    return bullets


def _uncoupled_chordwise(table: pd.DataFrame, curves) -> list[float]:
    """Our chordwise frequency without the axial coupling at each row's gamma (from
    ``rotating_eigen.nc``; NaN for other directions, other alpha, or gamma off the curve grid)."""
    grid = curves["gamma"].values
    values = curves["omega_chordwise_uncoupled"].values
    out = []
    for _, row in table.iterrows():
        hit = np.flatnonzero(np.isclose(grid, row["gamma"], rtol=0.0, atol=1e-9))
        alpha = float(row["alpha"])
        same_beam = not math.isnan(alpha) and math.isclose(alpha, float(curves.attrs["alpha"]))
        out.append(float(values[hit[0]]) if row["direction"] == "chordwise" and same_beam and len(hit)
                   else math.nan)
    return out


def published_section(comparison_csv, tip_mass_csv, curves_nc, figure, report_dir) -> Section:
    """The "Validation" section of the reproduction report (module docstring)."""
    table = read_result_table(comparison_csv, PUBLISHED_COLUMNS, BUILD_PUBLISHED)
    tip = read_result_table(tip_mass_csv, TIP_MASS_COLUMNS, BUILD_PUBLISHED)
    curves = open_result(curves_nc)
    counts = _mode_columns(table, "omega_n", comparison_csv)
    n_ours, ours = counts[-1]
    n_tip, tip_ours = _mode_columns(tip, "root_n", tip_mass_csv)[-1]
    estimate = f"the change from {counts[-2][0]} to {n_ours} modes" if len(counts) > 1 else "none"
    table["uncoupled"] = _uncoupled_chordwise(table, curves)
    agree, total = int(table["agrees"].sum()), len(table)
    tip_agree, tip_total = int(tip["agrees"].sum()), len(tip)
    sources = [key for key in published.CITATIONS if key in "+".join(table["source"])]
    summary = (f"Independent validation: **{agree} of {total}** published rotating-cantilever first "
               f"frequencies and **{tip_agree} of {tip_total}** first roots of the tip-mass frequency "
               "equation are reproduced (section Validation).")
    out = [
        "## Validation",
        "",
        "### Published rotating-cantilever frequencies",
        "",
        "The constant-speed linearisation of FOAM (Eqs. 29-31 at a fixed hub speed, with the "
        "Coriolis coupling of the axial and transverse coordinates) is compared with first "
        "frequencies of uniform rotating cantilevers published independently of the paper, by "
        f"{', '.join(published.short_name(s) for s in sources)}, and with the first roots of the "
        "frequency equation of a non-rotating cantilever with a tip mass. The sources' dimensionless "
        "form is used: speed ratio gamma = Omega sqrt(rho A L^4 / (E I)), frequency omega_bar = "
        "omega sqrt(rho A L^4 / (E I)), slenderness alpha = sqrt(A L^2 / I), hub radius ratio "
        "delta = r_A / L, tip-mass ratio mu = m_t / (rho A L); flapwise is out of the plane of "
        "rotation, chordwise in it. Derivation and evidence: `docs/validation.md`.",
        "",
        f"**Result.** {agree} of {total} published rotating first frequencies and {tip_agree} of "
        f"{tip_total} tip-mass roots agree. An entry agrees when ours ({n_ours} assumed modes) minus "
        "the printed value lies in the interval of exact values the printed digits stand for (last "
        "digit rounded: within half a unit u of the last printed place; truncated: from 0 to one "
        f"unit), widened on both sides by our modal-truncation estimate ({estimate}).",
        "",
    ]
    failing = table[~table["agrees"]]
    if len(failing):
        out += ["Entries that do not agree: " + "; ".join(
            f"{published.short_name(row['source'])}, {row['direction']} gamma = {row['gamma']:g}: "
            f"printed {row['printed']}, ours {row[ours]:.6f}" for _, row in failing.iterrows()) + ".", ""]
    out += ["**How the last printed digit was obtained.** The sources do not say; each reading is "
            "tested against our converged values:", ""]
    out += [f"- {bullet}" for bullet in _reading_evidence(table, ours)]
    out += ["", "The truncated reading is not a wider tolerance: it is a one-sided test "
            "(0 <= ours - printed < u) of the same width as the rounded one.", ""]
    loose = table[~table.apply(_resolved, axis=1)]
    if len(loose):
        listed = "; ".join(f"{row['direction']} gamma = {row['gamma']:g}: {_g(row['modal_change'])} "
                           f"({_percent(row['modal_change'] / row['published'])} of the value), ours "
                           f"minus printed {_g(row['difference'])}" for _, row in loose.iterrows())
        out += [f"**Limits.** Where our truncation estimate exceeds half a printed unit, agreement is "
                f"confirmed only to within that estimate: {listed}.", ""]
    coupled = table[np.isfinite(table["uncoupled"]) & table.apply(_resolved, axis=1)]
    if len(coupled):
        row = coupled.loc[coupled["gamma"].idxmax()]
        out += [f"**Axial coupling.** Without the Coriolis coupling to the axial coordinates the "
                f"chordwise first frequency at gamma = {row['gamma']:g} would be "
                f"{row['uncoupled']:.4f} against the printed {row['printed']}; with it, ours is "
                f"{row[ours]:.6f} (column 'no axial coupling' below).", ""]
    out += [
        "| source | direction | gamma | alpha | printed | reading | ours | ours - printed | agreement interval "
        "| no axial coupling | verdict |",
        "|---|---|---:|---:|---:|---|---:|---:|---|---:|---|",
    ]
    for _, row in table.iterrows():
        alpha = "-" if math.isnan(float(row["alpha"])) else f"{row['alpha']:g}"
        uncoupled = "-" if math.isnan(row["uncoupled"]) else f"{row['uncoupled']:.4f}"
        out.append(f"| {published.short_name(row['source'])} | {row['direction']} | {row['gamma']:g} | "
                   f"{alpha} | {row['printed']} | {row['rounding']} | {row[ours]:.6f} | "
                   f"{row['difference']:+.1e} | [{row['allowed_low']:+.1e}, {row['allowed_high']:+.1e}] | "
                   f"{uncoupled} | **{'agrees' if row['agrees'] else 'differs'}** |")
    out += ["", f"Non-rotating cantilever with a point mass m_t at its tip: first root beta_1 L of "
            "1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0 (printed values read as "
            f"{published.ROUNDING['tip-mass-frequency-equation']}), ours from the assumed-mode "
            f"model with {n_tip} modes.", "",
            "| mu | printed | ours | ours - printed | agreement interval | verdict |",
            "|---:|---:|---:|---:|---|---|"]
    for _, row in tip.iterrows():
        out.append(f"| {row['mu']:g} | {row['printed']} | {row[tip_ours]:.6f} | {row['difference']:+.1e} | "
                   f"[{row['allowed_low']:+.1e}, {row['allowed_high']:+.1e}] | "
                   f"**{'agrees' if row['agrees'] else 'differs'}** |")
    out += ["", f"![Validation: first frequencies of the rotating cantilever ({curves.attrs['n_modes']} "
            f"modes, alpha = {curves.attrs['alpha']:g}) against the published values]"
            f"({_link(figure, report_dir)})", ""]
    out += [
        "### Geometrically exact reference (Exudyn)",
        "",
        "The comparison of FOAM, CFOAM and TLAM with a geometrically exact multibody model of the "
        "same hub-beam (Exudyn, ANCF cable elements) needs the optional dependency "
        "(`pip install -e .[validation]`) and is not part of this report: run `snakemake validate` "
        "to build its own report, [validation_exudyn.html](validation_exudyn.html) "
        "(`results/report/validation_exudyn.md`), beside this one.",
        "",
        "### Sources of the published values",
        "",
    ]
    out += [f"- {published.CITATIONS[key]}" for key in published.CITATIONS
            if key in "+".join(table["source"]) or key == "tip-mass-frequency-equation"]
    return Section(summary, "\n".join(out) + "\n")


# --- the Exudyn comparison ------------------------------------------------------------------------

def _ratio_text(ratios) -> str:
    if (ratios > 1.0).all():
        return ("It is in every case further from the geometrically exact beam than FOAM: it keeps "
                "more terms of the same approximate deformation field, not the terms of that order "
                "the field itself neglects (docs/validation.md).")
    if (ratios < 1.0).all():
        return "It is in every case closer to the geometrically exact beam than FOAM."
    return "It is closer to the geometrically exact beam than FOAM in some cases, further in others."


def exudyn_findings(comparison: pd.DataFrame, mode_study: pd.DataFrame,
                    convergence: pd.DataFrame) -> list[str]:
    """The key findings of docs/validation.md, computed from the three tables (Markdown bullets)."""
    bullets = []
    by_model = {model: rows.set_index("case") for model, rows in comparison.groupby("model")}
    foam = by_model.get("FOAM")
    if foam is not None:
        bounded = foam[foam["diverged"] == 0]
        worst = bounded["max_abs_difference_rel_peak"].idxmax()
        text = (f"**FOAM** stays within {_percent(bounded['max_abs_difference_rel_peak'].max())} of "
                f"the reference's peak tip deflection in all {len(bounded)} bounded cases (largest "
                f"difference {_g(bounded['max_abs_difference_m'].max())} m, {_case_label(bounded.loc[worst])}); "
                f"its residual vibration amplitude is within "
                f"{_percent((bounded['residual_ratio'] - 1.0).abs().max())} of the reference's.")
        if len(bounded) < len(foam):
            text += f" It diverges in {len(foam) - len(bounded)} case(s)."
        bullets.append(text)
        cfoam = by_model.get("CFOAM")
        if cfoam is not None:
            common = cfoam.index.intersection(bounded.index)
            ratios = cfoam.loc[common, "max_abs_difference_m"] / bounded.loc[common, "max_abs_difference_m"]
            bullets.append(
                f"**CFOAM**'s largest tip difference from the reference is {_range(ratios.values)} "
                f"times FOAM's ({len(common)} cases), at most "
                f"{_percent(cfoam.loc[common, 'max_abs_difference_rel_peak'].max())} of the peak. "
                f"{_ratio_text(ratios)}")
    tlam = by_model.get("TLAM")
    if tlam is not None:
        parts = []
        for _, row in tlam.reset_index().iterrows():
            if row["diverged"]:
                parts.append(f"diverges at {_case_label(row)} (t = {row['diverged_at_s']:.1f} s)")
            else:
                parts.append(f"at {_case_label(row)} its peak is {row['peak_m'] / row['peak_reference_m']:.2f} "
                             f"times the reference's and its residual amplitude {row['residual_ratio']:.3g} "
                             "times")
        bullets.append("**TLAM**: " + "; ".join(parts) + ".")
    counts = sorted(mode_study["n_modes"].unique())
    if len(counts) >= 2:
        previous, last = counts[-2], counts[-1]
        parts = []
        for model, rows in mode_study.groupby("model", sort=False):
            pivot = rows.pivot(index="case", columns="n_modes", values="max_abs_difference_m")
            pivot = pivot.reindex(columns=[previous, last]).dropna()
            if len(pivot):
                change = (pivot[last] - pivot[previous]).abs() / pivot[last]
                parts.append(f"{model} {_range(change.values, scale=100.0, unit=' %')} "
                             f"({len(change)} case{'s' if len(change) > 1 else ''})")
        bullets.append(f"**Mode study**: from {previous} to {last} modes the largest difference from "
                       f"the reference changes by {'; '.join(parts)}. A difference that no longer "
                       "changes with the modes is one of the equations, not of the modal truncation.")
    production = convergence[convergence["production"] == 1]
    if len(production) and foam is not None:
        error = production["max_abs_difference_to_finest_m"].max()
        smallest = foam.loc[foam["diverged"] == 0, "max_abs_difference_m"].min()
        bullets.append(f"**Reference accuracy**: the production Exudyn run differs from the finest run "
                       f"of each convergence study by at most {_g(error, 2)} m, "
                       f"{smallest / error:.0f} times below FOAM's smallest difference "
                       f"({_g(smallest)} m).")
    return bullets


def _convergence_tables(convergence: pd.DataFrame) -> list[str]:
    headers = {"elements": "elements", "time_step": "time step (s)",
               "newton_tolerance": "Newton tolerance"}
    out = []
    for study, rows in convergence.groupby("study", sort=False):
        out += [f"| {headers.get(study, study)} | production | max. difference to the finest run (m) | "
                "max. difference to the next finer run (m) | Newton iterations | wall time (s) |",
                "|---:|---|---:|---:|---:|---:|"]
        for _, row in rows.iterrows():
            out.append(f"| {row['value']:g} | {'yes' if row['production'] else ''} | "
                       f"{_g(row['max_abs_difference_to_finest_m'], 2)} | "
                       f"{_g(row['max_abs_difference_to_next_finer_m'], 2)} | "
                       f"{int(row['newton_iterations'])} | {row['cpu_time_s']:.1f} |")
        out.append("")
    return out


def exudyn_markdown(comparison_csv, mode_study_csv, convergence_csv, figure, report_dir) -> str:
    """The report of the Exudyn comparison, ``results/report/validation_exudyn.md``."""
    comparison = read_result_table(comparison_csv, COMPARISON_COLUMNS, BUILD_EXUDYN)
    mode_study = read_result_table(mode_study_csv, MODE_STUDY_COLUMNS, BUILD_EXUDYN)
    convergence = read_result_table(convergence_csv, CONVERGENCE_COLUMNS, BUILD_EXUDYN)
    production = convergence[convergence["production"] == 1]
    settings = (f"{int(production['elements'].iloc[0])} elements, a fixed step of "
                f"{production['time_step_s'].iloc[0]:g} s and a Newton increment tolerance of "
                f"{production['newton_tolerance'].iloc[0]:g}") if len(production) else "see below"
    cases = comparison.drop_duplicates("case")
    out = [
        "# Validation against a geometrically exact reference (Exudyn)",
        "",
        f"Generated by hubbeam {__version__} from the results of `snakemake validate` only "
        "(`results/validation/exudyn_comparison.csv`, `exudyn_mode_study.csv`, "
        "`exudyn_convergence.csv`); the method is described in `docs/validation.md`, the comparison "
        "with published frequency tables and the paper's claims in "
        "[the reproduction report](reproduction.html).",
        "",
        "The hub-beam of Table 1 is modelled with Exudyn's 2D ANCF cable elements (exact kinematics: "
        "large rotation, stretch and foreshortening) with the clamp rotated as the spin-up of Eq. 43 "
        f"prescribes, integrated by the generalised-alpha method ({settings}). The models "
        f"{', '.join(comparison['model'].unique())} run with "
        f"{_range(comparison['n_modes'].values, digits=3)} modes. Cases: "
        + "; ".join(f"{row['case']} ({_case_label(row)}, t_f = {row['tf']:g} s)"
                    for _, row in cases.iterrows()) + ".",
        "",
        "## Key findings",
        "",
    ]
    out += [f"- {bullet}" for bullet in exudyn_findings(comparison, mode_study, convergence)]
    out += ["", "## Tip deflection against the reference", "",
            "Largest difference |v_model - v_Exudyn| over the run, relative to the reference's peak; "
            "peak max |v|; residual amplitude max |v| after the spin-up (t > t_f). A diverged run "
            "(its time is given) has no measures.", "",
            "| case | model | max. difference (m) | / reference peak | peak (m) | reference peak (m) | "
            "residual (m) | reference residual (m) | diverged at (s) |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for _, row in comparison.iterrows():
        reference = f"{_g(row['peak_reference_m'], 5)} | "
        if row["diverged"]:  # measures of a run that left the frame say nothing
            ours = f"- | - | - | {reference}- | {_g(row['residual_reference_m'], 4)} | {row['diverged_at_s']:.2f}"
        else:
            ours = (f"{_g(row['max_abs_difference_m'])} | {_percent(row['max_abs_difference_rel_peak'])} | "
                    f"{_g(row['peak_m'], 5)} | {reference}{_g(row['residual_m'], 4)} | "
                    f"{_g(row['residual_reference_m'], 4)} | -")
        out.append(f"| {row['case']} | {row['model']} | {ours} |")
    out += ["", f"![Tip deflection of the models and the Exudyn reference (left) and their difference "
            f"(right)]({_link(figure, report_dir)})", "",
            "## Difference against the number of assumed modes", "",
            "Largest tip-deflection difference from the reference (m); diverged runs are left out.", ""]
    counts = sorted(mode_study["n_modes"].unique())
    out += ["| case | model | " + " | ".join(f"n = {n}" for n in counts) + " |",
            "|---|---|" + "---:|" * len(counts)]
    for (case, model), rows in mode_study.groupby(["case", "model"], sort=False):
        values = dict(zip(rows["n_modes"], rows["max_abs_difference_m"]))
        out.append(f"| {case} | {model} | " + " | ".join(_g(values.get(n, math.nan)) for n in counts) + " |")
    out += ["", "## Convergence of the reference", "",
            "Each study varies one setting of the production run; differences are the largest "
            "tip-deflection differences over the run.", ""]
    out += _convergence_tables(convergence)
    out += ["## Sources", ""] + [f"- {source}" for source in EXUDYN_SOURCES]
    return "\n".join(out) + "\n"
