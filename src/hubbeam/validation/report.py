"""The validation parts of the reports, written from the validation result files only.

* :func:`published_section` -- the "Validation" section of the reproduction report: the
  constant-speed linearisation of FOAM against the published first frequencies of rotating
  cantilevers (Wright et al. 1982; Hodges and Rutkowski 1981; Hamza-Cherif and Houmat 2004) and
  the tip-mass frequency equation, from the files of rule ``validate_published``
  (``published_comparison.csv``, ``tip_mass_comparison.csv``, ``rotating_eigen.nc`` and the figure).
* :func:`validation_markdown` -- the report of ``snakemake validate``
  (``results/[<study>/]report/validation_exudyn.md``): the comparison with the Exudyn ANCF
  reference (``exudyn_comparison.csv``, ``exudyn_mode_study.csv``, ``exudyn_convergence.csv``, the
  figure) when the config has a ``validation`` section, and the frequencies of a non-uniform beam
  from the Ritz model, our finite elements and pyBModes (``nonuniform_ritz_fe.csv``,
  ``nonuniform_pybmodes.csv``).

Every number of the text (counts, ratios, the evidence for how a table's last digit was
obtained, the key findings of docs/validation.md) is computed here from those files; none is
typed in; the prose is in the templates ``validation_published.md.j2`` and
``validation_exudyn.md.j2``. A missing file raises :class:`hubbeam.results.io.ResultFileError` naming it
and the command that builds it; a file without a needed column raises
:class:`ValidationInputError`.
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
from hubbeam.reporting.document import markdown_table, render
from hubbeam.reporting.formatting import fixed, number, percent, scientific
from hubbeam.results.io import ResultFileError, open_result
from hubbeam.validation import nonuniform, published
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
NONUNIFORM_COLUMNS = ("direction", "speed_rad_s", "mode", "n_modes", "ritz_hz", "fe_hz", "rel_diff",
                      "case", "tip_mass_kg")
PYBMODES_COLUMNS = ("direction", "speed_rad_s", "mode", "pybmodes_hz", "order", "rel_diff_ritz",
                    "rel_diff_fe")
CONVERGENCE_COLUMNS = ("study", "value", "elements", "time_step_s", "newton_tolerance", "production",
                       "max_abs_difference_to_finest_m", "max_abs_difference_to_next_finer_m",
                       "newton_iterations", "cpu_time_s")

#: how each validation file is built (for the error naming a missing one)
BUILD_PUBLISHED = "`snakemake {path}` (rule validate_published, part of `snakemake`)"
BUILD_EXUDYN = "`snakemake validate` (needs the Exudyn extra: `pip install -e .[validation]`)"

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

def _range(values, digits: int = 2, scale: float = 1.0, unit: str = "") -> str:
    """``"a to b"`` (or ``"a"`` when equal at the shown precision) of ``values * scale``."""
    low, high = (number(scale * float(v), digits) for v in (np.min(values), np.max(values)))
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


def _difference_cells(row) -> list[str]:
    """Ours minus printed and the interval it must lie in to agree."""
    low, high = (scientific(row[key], 1, signed=True) for key in ("allowed_low", "allowed_high"))
    return [scientific(row["difference"], 1, signed=True), f"[{low}, {high}]"]


def _verdict(row) -> str:
    return f"**{'agrees' if row['agrees'] else 'differs'}**"


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
    failing = [f"{published.short_name(row['source'])}, {row['direction']} gamma = {row['gamma']:g}: "
               f"printed {row['printed']}, ours {row[ours]:.6f}"
               for _, row in table[~table["agrees"]].iterrows()]
    loose = [f"{row['direction']} gamma = {row['gamma']:g}: {number(row['modal_change'], 3)} "
             f"({percent(row['modal_change'] / row['published'])} of the value), ours "
             f"minus printed {number(row['difference'], 3)}"
             for _, row in table[~table.apply(_resolved, axis=1)].iterrows()]
    coupled = table[np.isfinite(table["uncoupled"]) & table.apply(_resolved, axis=1)]
    if len(coupled):
        row = coupled.loc[coupled["gamma"].idxmax()]
        coupled = {"gamma": f"{row['gamma']:g}", "uncoupled": f"{row['uncoupled']:.4f}",
                   "printed": row["printed"], "ours": f"{row[ours]:.6f}"}
    else:
        coupled = None
    published_table = markdown_table(
        ("source", "direction", "gamma", "alpha", "printed", "reading", "ours", "ours - printed",
         "agreement interval", "no axial coupling", "verdict"),
        ([published.short_name(row["source"]), row["direction"], number(row["gamma"], 6),
          number(float(row["alpha"]), 6), row["printed"], row["rounding"], fixed(row[ours], 6),
          *_difference_cells(row), fixed(row["uncoupled"], 4), _verdict(row)] for _, row in table.iterrows()),
        "llrrrlrrlrl")
    tip_table = markdown_table(
        ("mu", "printed", "ours", "ours - printed", "agreement interval", "verdict"),
        ([number(row["mu"], 6), row["printed"], fixed(row[tip_ours], 6), *_difference_cells(row), _verdict(row)]
         for _, row in tip.iterrows()), "rrrrll")
    markdown = render(
        "validation_published.md.j2", sources=[published.short_name(s) for s in sources],
        agree=agree, total=total, tip_agree=tip_agree, tip_total=tip_total, n_ours=n_ours,
        estimate=estimate, failing=failing, evidence=_reading_evidence(table, ours), loose=loose,
        coupled=coupled, published_table=published_table,
        tip_rounding=published.ROUNDING["tip-mass-frequency-equation"], n_tip=n_tip, tip_table=tip_table,
        curve_modes=curves.attrs["n_modes"],
        alpha=f"{curves.attrs['alpha']:g}", figure=_link(figure, report_dir),
        citations=[published.CITATIONS[key] for key in published.CITATIONS
                   if key in "+".join(table["source"]) or key == "tip-mass-frequency-equation"])
    return Section(summary, markdown)


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
        text = (f"**FOAM** stays within {percent(bounded['max_abs_difference_rel_peak'].max())} of "
                f"the reference's peak tip deflection in all {len(bounded)} bounded cases (largest "
                f"difference {number(bounded['max_abs_difference_m'].max(), 3)} m, {_case_label(bounded.loc[worst])}); "
                f"its residual vibration amplitude is within "
                f"{percent((bounded['residual_ratio'] - 1.0).abs().max())} of the reference's.")
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
                f"{percent(cfoam.loc[common, 'max_abs_difference_rel_peak'].max())} of the peak. "
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
                       f"of each convergence study by at most {number(error, 2)} m, "
                       f"{smallest / error:.0f} times below FOAM's smallest difference "
                       f"({number(smallest, 3)} m).")
    return bullets


def _convergence_tables(convergence: pd.DataFrame) -> list[str]:
    """One table per convergence study of the reference."""
    headers = {"elements": "elements", "time_step": "time step (s)",
               "newton_tolerance": "Newton tolerance"}
    return [markdown_table(
        (headers.get(study, study), "production", "max. difference to the finest run (m)",
         "max. difference to the next finer run (m)", "Newton iterations", "wall time (s)"),
        ([number(row["value"], 6), "yes" if row["production"] else "",
          number(row["max_abs_difference_to_finest_m"], 2), number(row["max_abs_difference_to_next_finer_m"], 2),
          int(row["newton_iterations"]), fixed(row["cpu_time_s"], 1)] for _, row in rows.iterrows()),
        "rlrrrr") for study, rows in convergence.groupby("study", sort=False)]


def _comparison_cells(row) -> list:
    """A line of the tip-deflection comparison; a diverged run has no measures but its time."""
    reference = [number(row["peak_reference_m"], 5)]
    if row["diverged"]:  # measures of a run that left the frame say nothing
        return [row["case"], row["model"], "-", "-", "-", *reference, "-", number(row["residual_reference_m"], 4),
                fixed(row["diverged_at_s"], 2)]
    return [row["case"], row["model"], number(row["max_abs_difference_m"], 3),
            percent(row["max_abs_difference_rel_peak"]), number(row["peak_m"], 5), *reference,
            number(row["residual_m"], 4), number(row["residual_reference_m"], 4), "-"]


def _exudyn_context(comparison_csv, mode_study_csv, convergence_csv, figure, report_dir) -> dict:
    """The template variables of the Exudyn part of the validation report."""
    comparison = read_result_table(comparison_csv, COMPARISON_COLUMNS, BUILD_EXUDYN)
    mode_study = read_result_table(mode_study_csv, MODE_STUDY_COLUMNS, BUILD_EXUDYN)
    convergence = read_result_table(convergence_csv, CONVERGENCE_COLUMNS, BUILD_EXUDYN)
    production = convergence[convergence["production"] == 1]
    settings = (f"{int(production['elements'].iloc[0])} elements, a fixed step of "
                f"{production['time_step_s'].iloc[0]:g} s and a Newton increment tolerance of "
                f"{production['newton_tolerance'].iloc[0]:g}") if len(production) else "see below"
    cases = comparison.drop_duplicates("case")
    comparison_table = markdown_table(
        ("case", "model", "max. difference (m)", "/ reference peak", "peak (m)", "reference peak (m)",
         "residual (m)", "reference residual (m)", "diverged at (s)"),
        (_comparison_cells(row) for _, row in comparison.iterrows()), "llrrrrrrr")
    counts = sorted(mode_study["n_modes"].unique())
    mode_table = markdown_table(
        ("case", "model", *(f"n = {n}" for n in counts)),
        ([case, model, *(number(dict(zip(rows["n_modes"], rows["max_abs_difference_m"])).get(n, math.nan), 3)
                         for n in counts)]
         for (case, model), rows in mode_study.groupby(["case", "model"], sort=False)),
        "ll" + "r" * len(counts))
    return dict(
        settings=settings,
        models=list(comparison["model"].unique()), modes=_range(comparison["n_modes"].values, digits=3),
        cases=[f"{row['case']} ({_case_label(row)}, t_f = {row['tf']:g} s)" for _, row in cases.iterrows()],
        findings=exudyn_findings(comparison, mode_study, convergence), comparison_table=comparison_table,
        figure=_link(figure, report_dir), mode_table=mode_table,
        convergence_tables=_convergence_tables(convergence))


# --- non-uniform beams ----------------------------------------------------------------------------

def _nonuniform_context(ritz_fe_csv, pybmodes_csv=None) -> dict:
    """The template variables of the non-uniform checks: per case (bare beam, tip mass) and mode
    count the largest |Ritz / FE - 1| over directions, speeds and the compared modes; per model
    the largest |ours / pyBModes - 1| and the observed orders of pyBModes's meshes."""
    ritz_fe = read_result_table(ritz_fe_csv, NONUNIFORM_COLUMNS, BUILD_EXUDYN)
    worst = (ritz_fe.assign(error=ritz_fe["rel_diff"].abs())
             .pivot_table(index="case", columns="n_modes", values="error", aggfunc="max"))
    counts = list(worst.columns)
    masses = ritz_fe.groupby("case")["tip_mass_kg"].first()
    ritz_table = markdown_table(
        ("case", "tip mass (kg)", *(f"n = {n}" for n in counts)),
        ([case, number(float(masses[case]), 4), *(number(row[n], 2) for n in counts)]
         for case, row in worst.iterrows()), "lr" + "r" * len(counts))
    context = dict(ritz_table=ritz_table, speeds=_range(ritz_fe["speed_rad_s"].unique(), digits=3),
                   frequencies=int(ritz_fe["mode"].max()), ritz_best=number(worst[counts[-1]].max(), 2),
                   ritz_modes=int(counts[-1]), speed_ratios=[f"{r:g}" for r in nonuniform.SPEED_RATIOS],
                   taper=f"{nonuniform.TAPER_RATIO:g}", tip_ratio=f"{nonuniform.TIP_MASS_RATIO:g}",
                   fe_elements=nonuniform.FE_ELEMENTS, pybmodes=None)
    if pybmodes_csv is not None:
        table = read_result_table(pybmodes_csv, PYBMODES_COLUMNS, BUILD_EXUDYN)
        context["pybmodes"] = dict(
            ritz=number(table["rel_diff_ritz"].abs().max(), 2), fe=number(table["rel_diff_fe"].abs().max(), 2),
            order=_range(table["order"].values, digits=3), rows=len(table),
            meshes=list(nonuniform.PYBMODES_MESHES))
    return context


def validation_markdown(report_dir, ritz_fe_csv, pybmodes_csv=None, exudyn=None) -> str:
    """The validation report ``RESULTS/report/validation_exudyn.md``: the non-uniform checks
    (``nonuniform_ritz_fe.csv``, ``nonuniform_pybmodes.csv`` when pyBModes ran) and, given
    ``exudyn`` = ``{"comparison", "mode_study", "convergence", "figure"}`` (paths), the
    comparison with the Exudyn reference."""
    exudyn_context = None
    if exudyn is not None:
        exudyn_context = _exudyn_context(exudyn["comparison"], exudyn["mode_study"],
                                         exudyn["convergence"], exudyn["figure"], report_dir)
    return render("validation_exudyn.md.j2", version=__version__, exudyn=exudyn_context,
                  nonuniform=_nonuniform_context(ritz_fe_csv, pybmodes_csv))
