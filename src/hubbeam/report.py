"""The reproduction report: the figures of the registry with the paper's and our text, the claims
with their verdicts, the tables, the validation and the simulation runs (Markdown from the template
``templates/reproduction.md.j2``; HTML by :func:`hubbeam.document.markdown_to_html`).

The claims are evaluated by :mod:`hubbeam.claims` (``claims.csv``), the captions come from
:data:`hubbeam.products.PAPER_PRODUCTS`, and the measures are those of :mod:`hubbeam.measures`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path

import xarray as xr

from hubbeam import __version__, validity
from hubbeam.document import render
from hubbeam.products import PAPER_PRODUCTS, Product
from hubbeam.results import maneuver, model, n_modes, tip_mass, tip_position


def _format(value, digits=4) -> str:
    if value is None or value == "" or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def _md_cell(text: str) -> str:
    return str(text).replace("|", "\\|")


def claims_markdown(rows: list[dict]) -> str:
    lines = ["| id | claim | unit | paper | computed | rel. diff. | verdict |",
             "|---|---|---|---:|---:|---:|---|"]
    for row in rows:
        rel = row.get("rel_diff")
        rel_text = "-" if rel in ("", None) or (isinstance(rel, float) and math.isnan(rel)) else f"{100 * rel:+.2f} %"
        lines.append(f"| `{row['id']}` | {_md_cell(row['claim'])} | {row['unit']} | {_format(row['paper'])} | "
                     f"{_format(row['computed'])} | {rel_text} | **{row['verdict']}** |")
    return "\n".join(lines)


def runs_markdown(datasets: Mapping[str, xr.Dataset]) -> str:
    """The settings of every simulation run, read from the datasets' attributes."""
    lines = ["| case | model | n | maneuver | t_end (s) | tip mass (kg) at l (m) | validity | steps |",
             "|---|---|---:|---|---:|---|---|---:|"]
    for case, ds in sorted(datasets.items()):
        man = maneuver(case, ds)
        law = ", ".join(f"{k} = {v:g}" if isinstance(v, (int, float)) else f"{k} = {v}" for k, v in man.items())
        mass = tip_mass(case, ds)
        where = f"{mass:g} at {tip_position(case, ds):g}" if mass else "none"
        lines.append(f"| {case} | {model(case, ds)} | {n_modes(case, ds)} | {law} | "
                     f"{float(ds['time'].values[-1]):g} | {where} | {validity.describe(ds.attrs)} | "
                     f"{ds.attrs.get('n_steps', '-')} |")
    return "\n".join(lines)


def reproduction_markdown(claim_rows: list[dict], figures: Mapping[str, str | Path],
                          tables: Mapping[str, str | Path], datasets: Mapping[str, xr.Dataset],
                          numerics: Mapping, report_dir, validation=None, readings=None,
                          products: Mapping[str, Product] = PAPER_PRODUCTS) -> str:
    """The reproduction report (Markdown), figures linked relative to ``report_dir``.

    ``figures`` maps product keys to image files; each figure of ``products`` that is given gets a
    section with its caption and the claims it carries. ``validation`` is the
    :class:`hubbeam.validation.report.Section` of the published-table validation (its summary
    sentence joins the report's summary), or None when the configuration has no ``validation``
    section. ``readings`` is the section of :func:`hubbeam.explain.section` (None without a
    ``readings`` section in the configuration).
    """
    report_dir = Path(report_dir).resolve()
    by_id = {row["id"]: row for row in claim_rows}
    commits = sorted({str(ds.attrs.get("git_commit", "unknown")) for ds in datasets.values()})
    sections = []
    for key, product in products.items():
        if not product.is_figure or key not in figures:
            continue
        listed = [by_id[c] for c in product.claims if c in by_id]
        sections.append({
            "title": product.title, "paper": product.paper, "ours": product.ours,
            "link": Path(os.path.relpath(Path(figures[key]).resolve(), report_dir)).as_posix(),
            "claims": claims_markdown(listed) if listed else ""})
    differing = [{"id": row["id"], "paper": _format(row["paper"]), "computed": _format(row["computed"]),
                  "unit": "" if row["unit"] == "1" else f" {row['unit']}"}
                 for row in claim_rows if row["verdict"] == "differs"]
    return render(
        "reproduction.md.j2", version=__version__, commits=", ".join(f"`{c}`" for c in commits),
        numerics={key: numerics.get(key) for key in ("rtol", "atol", "output_step", "quadrature_points")},
        claims=claim_rows, validation=validation, readings=readings, differing=differing,
        counts={v: sum(r["verdict"] == v for r in claim_rows) for v in ("agrees", "differs", "qualitative")},
        tables=[Path(tables[name]).read_text().strip() for name in sorted(tables)],
        figures=sections, all_claims=claims_markdown(claim_rows), runs=runs_markdown(datasets))
