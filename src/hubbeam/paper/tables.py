"""Tables 1-3 of the paper as csv (full precision) with Markdown and LaTeX renderings beside.

- Table 1: the physical parameters of the configuration, beside the printed ones.
- Table 2: the first five vibration frequencies (Hz); its csv is written by the eigen rule
  (``hubbeam.model.eigen.table2``), this module only renders it. The journal swaps the captions of
  Tables 2 and 3 (reproduction note 3); the captions here are the corrected ones.
- Table 3: the largest |Q_theta| (Eq. 32) under the torque pulse of Eq. 44 for each tau_max,
  computed from the FOAM torque runs, beside the printed values (reproduction note 9).
"""

from __future__ import annotations

import csv
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from hubbeam.model import printed as paper
from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import csv_cell, number
from hubbeam.results.measures import peak
from hubbeam.results.reader import maneuver_value, model, n_modes, variable


class Text(str):
    """A text cell with its own LaTeX spelling (e.g. a symbol): ``Text("J_h", latex="$J_h$")``."""

    def __new__(cls, text: str, latex: str | None = None):
        self = super().__new__(cls, text)
        self.latex = latex
        return self


@dataclass(frozen=True)
class Column:
    """One column: ``key`` heads the csv, ``title`` the Markdown, ``latex`` the LaTeX table."""

    key: str
    title: str
    latex: str
    digits: int | None = 4  # significant digits in Markdown/LaTeX; None: print as text


@dataclass(frozen=True)
class Table:
    name: str
    caption: str
    columns: tuple[Column, ...]
    rows: tuple[dict, ...]


# --- writers ------------------------------------------------------------------------------------

def _is_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def format_value(value, digits: int | None, *, latex: bool = False) -> str:
    """``digits`` significant digits (:func:`hubbeam.reporting.formatting.number`); powers of ten as
    ``x 10^k`` (Markdown) or ``\\times 10^{k}`` (LaTeX); text as it is (escaped for LaTeX, or
    its own LaTeX spelling); ``-`` when missing."""
    if latex and getattr(value, "latex", None):
        return value.latex
    if digits is None or not _is_number(value):
        text = number(value)
        return _latex_escape(text) if latex else text
    return number(value, digits, power="latex" if latex else "unicode")


def _latex_escape(text: str) -> str:
    return re.sub(r"([&%#_{}])", r"\\\1", text)


def write_csv(table: Table, path) -> Path:
    return write_rows(table.rows, path, [c.key for c in table.columns])


def write_rows(rows, path, columns) -> Path:
    """``rows`` (mappings) as csv with ``columns``: numbers in full precision, NaN and None as
    empty cells (:func:`hubbeam.reporting.formatting.csv_cell`)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(columns)
        for row in rows:
            writer.writerow([csv_cell(row.get(column)) for column in columns])
    return path


def to_markdown(table: Table) -> str:
    cells = ([format_value(row.get(c.key), c.digits) for c in table.columns] for row in table.rows)
    align = "".join("l" if c.digits is None else "r" for c in table.columns)
    return (f"**{table.name}.** {table.caption}\n\n"
            + markdown_table([c.title for c in table.columns], cells, align) + "\n")


def to_latex(table: Table) -> str:
    spec = "".join("l" if c.digits is None else "r" for c in table.columns)
    label = re.sub(r"[^a-z0-9]", "", table.name.lower())
    lines = ["\\begin{table}[htbp]", "  \\centering",
             f"  \\caption{{{_latex_escape(table.caption)}}}", f"  \\label{{tab:{label}}}",
             f"  \\begin{{tabular}}{{{spec}}}", "    \\toprule",
             "    " + " & ".join(c.latex for c in table.columns) + " \\\\", "    \\midrule"]
    for row in table.rows:
        cells = [format_value(row.get(c.key), c.digits, latex=True) for c in table.columns]
        lines.append("    " + " & ".join(cells) + " \\\\")
    lines += ["    \\bottomrule", "  \\end{tabular}", "\\end{table}"]
    return "\n".join(lines) + "\n"


def write_table(table: Table, csv_path, *, csv: bool = True) -> list[Path]:
    """Write ``<stem>.csv`` (unless ``csv=False``), ``<stem>.md`` and ``<stem>.tex``."""
    csv_path = Path(csv_path)
    csv_path.parent.mkdir(parents=True, exist_ok=True)
    written = [write_csv(table, csv_path)] if csv else []
    for suffix, text in ((".md", to_markdown(table)), (".tex", to_latex(table))):
        path = csv_path.with_suffix(suffix)
        path.write_text(text)
        written.append(path)
    return written


def read_csv_rows(path, numeric_columns=None) -> list[dict]:
    """Rows of a csv with numeric cells as floats (empty cells: NaN); clear error if unreadable.

    With ``numeric_columns`` only those columns are converted (the others stay text, even when a
    cell looks like a number); otherwise every cell that parses as a number is.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"table file {path} does not exist (run the rule that writes it)")
    with path.open(newline="") as handle:
        rows = list(csv.DictReader(handle))
    if not rows:
        raise ValueError(f"table file {path} has no rows")

    def number(key, text):
        if numeric_columns is not None and key not in numeric_columns:
            return text
        try:
            return float(text) if text != "" else math.nan
        except ValueError:
            if numeric_columns is not None:
                raise ValueError(f"table file {path}: column {key!r} holds {text!r}, "
                                 "not a number") from None
            return text

    return [{key: number(key, value) for key, value in row.items()} for row in rows]


# --- Table 1 ------------------------------------------------------------------------------------

#: (config key of ``beam``, property, symbol in Markdown, symbol in LaTeX, unit, key of paper.TABLE1)
TABLE1_ROWS = (
    ("length", "Beam length", "L", "$L$", "m", "L"),
    ("density", "Mass per unit volume", "ρ", "$\\rho$", "kg m-3", "rho"),
    ("area", "Cross-section area", "A", "$A$", "m2", "A"),
    ("youngs_modulus", "Young's modulus", "E", "$E$", "N m-2", "E"),
    ("second_moment", "Beam area moment of inertia", "I", "$I$", "m4", "I"),
    ("hub_inertia", "Hub moment of inertia", "J_h", "$J_h$", "kg m2", "Jh"),
    ("hub_radius", "Hub radius", "r_A", "$r_A$", "m", "rA"),
)
_TEXT = lambda key, title, latex: Column(key, title, latex, None)  # noqa: E731


def table1(beam: Mapping[str, float]) -> Table:
    """Table 1 from the ``beam`` section of the config; the tip mass is the paper's
    (:data:`hubbeam.model.printed.TABLE1_TIP_MASS`), whatever tip masses the configured cases add."""
    rows = []
    for key, prop, symbol, tex, unit, paper_key in TABLE1_ROWS:
        if key not in beam:
            raise KeyError(f"beam.{key} missing from the configuration (needed for Table 1)")
        rows.append({"property": prop, "symbol": Text(symbol, tex), "value": float(beam[key]),
                     "unit": unit, "paper": paper.TABLE1[paper_key]})
    rows.append({"property": "Tip mass (at the beam tip)", "symbol": Text("m_t", "$m_t$"),
                 "value": paper.TABLE1_TIP_MASS, "unit": "kg",
                 "paper": paper.TABLE1_TIP_MASS})
    columns = (_TEXT("property", "Property", "Property"), _TEXT("symbol", "Symbol", "Symbol"),
               Column("value", "Value (this study)", "Value (this study)", 5),
               _TEXT("unit", "Unit", "Unit"), Column("paper", "Paper", "Paper", 5))
    return Table("Table 1", "Physical parameters of the hub-beam system (SI units).", columns,
                 tuple(rows))


# --- Table 2 ------------------------------------------------------------------------------------

def table2(csv_path, speed: float) -> Table:
    """Table 2 as written by the eigen rule: one row per mode, computed and printed columns."""
    rows = read_csv_rows(csv_path)
    titles = {"mode": ("Mode", "Mode")}
    for name in ("natural", "TLAM", "FOAM"):
        at = "" if name == "natural" else f" ({speed:g} rad/s)"
        label = "Natural" if name == "natural" else name
        titles[name] = (f"{label}{at}", f"{label}{at}")
        titles[f"paper_{name}"] = (f"{label}{at}, paper", f"{label}{at}, paper")
    columns = []
    for key in rows[0]:
        title, latex = titles.get(key, (key, _latex_escape(key)))
        columns.append(Column(key, title, latex, 6 if key != "mode" else None))
    rows = [row | {"mode": int(row["mode"])} if "mode" in row else row for row in rows]
    caption = (f"The first vibration frequencies (Hz) of the beam: natural (non-rotating), and "
               f"of TLAM and FOAM at a hub speed of {speed:g} rad/s, computed beside the printed "
               "values (the journal prints this table under Table 3's caption).")
    return Table("Table 2", caption, tuple(columns), tuple(rows))


# --- Table 3 ------------------------------------------------------------------------------------

def max_abs_q_theta(case: str, ds: xr.Dataset) -> float:
    """Largest |Q_theta| (N m) over the run (NaN samples after a divergence ignored)."""
    return peak(variable(case, ds, "Q_theta").values)


def table3_rows(datasets: Mapping[str, xr.Dataset]) -> list[dict]:
    """One row per tau_max of the FOAM torque runs: computed max |Q_theta| and the printed value."""
    printed = paper.TABLE3
    rows = []
    for case, ds in datasets.items():
        if model(case, ds) != "FOAM":
            continue
        tau = maneuver_value(case, ds, "tau_max")
        q = max_abs_q_theta(case, ds)
        ref = printed.get(tau, math.nan)
        rows.append({"tau_max": tau, "case": case, "n_modes": n_modes(case, ds),
                     "max_abs_Q_theta": q, "percent_of_tau_max": 100.0 * q / tau,
                     "paper": ref, "rel_diff": (q - ref) / abs(ref) if ref == ref else math.nan})
    if not rows:
        raise ValueError(f"Table 3 needs FOAM torque runs; got {sorted(datasets)}")
    return sorted(rows, key=lambda row: row["tau_max"])


def table3(datasets: Mapping[str, xr.Dataset]) -> Table:
    columns = (
        Column("tau_max", "τ_m (N m)", "$\\tau_m$ (N\\,m)", 4),
        _TEXT("case", "Case", "Case"),
        Column("n_modes", "n", "$n$", None),
        Column("max_abs_Q_theta", "max |Q_θ| (N m)", "$\\max|Q_\\theta|$ (N\\,m)", 3),
        Column("percent_of_tau_max", "max |Q_θ| / τ_m (%)", "$\\max|Q_\\theta|/\\tau_m$ (\\%)", 3),
        Column("paper", "Paper (N m)", "Paper (N\\,m)", 3),
        Column("rel_diff", "Relative difference", "Rel.\\ difference", 2),
    )
    caption = ("Largest inertia torque |Q_theta| (FOAM) under the torque pulse of Eq. 44 for each "
               "torque amplitude, beside the printed values (the journal prints this table under "
               "Table 2's caption; its values are not monotonic in the torque).")
    return Table("Table 3", caption, columns, tuple(table3_rows(datasets)))
