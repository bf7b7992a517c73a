"""The reproduction report: the figures of the registry with the paper's and our text, the claims
with their verdicts, the tables, the validation and the simulation runs (Markdown from the template
``reporting/templates/reproduction.md.j2``; HTML by :func:`hubbeam.reporting.document.markdown_to_html`).

The claims are evaluated by :mod:`hubbeam.paper.claims` (``claims.csv``), the captions come from
:data:`hubbeam.reporting.products.PAPER_PRODUCTS`, and the measures are those of :mod:`hubbeam.results.measures`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import xarray as xr

from hubbeam import __version__
from hubbeam.model import validity
from hubbeam.reporting.document import markdown_table, render
from hubbeam.reporting.formatting import number, percent
from hubbeam.reporting.products import PAPER_PRODUCTS, Product
from hubbeam.results.reader import maneuver, model, n_modes, times, tip_mass, tip_position


def claims_markdown(rows: list[dict]) -> str:
    return markdown_table(("id", "claim", "unit", "paper", "computed", "rel. diff.", "verdict"),
                          ([f"`{row['id']}`", row["claim"], row["unit"], number(row["paper"]),
                            number(row["computed"]), percent(row.get("rel_diff"), decimals=2, signed=True),
                            f"**{row['verdict']}**"] for row in rows), "lllrrrl")


def runs_markdown(datasets: Mapping[str, xr.Dataset]) -> str:
    """The settings of every simulation run, read from the datasets' attributes."""
    rows = []
    for case, ds in sorted(datasets.items()):
        law = ", ".join(f"{key} = {number(value, 6) if isinstance(value, (int, float)) else value}"
                        for key, value in maneuver(case, ds).items())
        mass = tip_mass(case, ds)
        where = f"{number(mass, 6)} at {number(tip_position(case, ds), 6)}" if mass else "none"
        rows.append([case, model(case, ds), n_modes(case, ds), law, number(float(times(ds)[-1]), 6), where,
                     validity.describe(ds.attrs), number(ds.attrs.get("n_steps"))])
    return markdown_table(("case", "model", "n", "maneuver", "t_end (s)", "tip mass (kg) at l (m)",
                           "validity", "steps"), rows, "llrlrllr")


def readings_markdown(readings: list[dict]) -> str:
    """The readings tested (:func:`hubbeam.paper.explain.section`): what each changes, its notes and
    how many claims it recomputes."""
    return markdown_table(("Reading", "Changes", "Notes", "Claims recomputed"),
                          ([f"`{r['name']}`", r["why"], r["notes"], r["claims"]] for r in readings))


def reproduction_markdown(claim_rows: list[dict], figures: Mapping[str, str | Path],
                          tables: Mapping[str, str | Path], datasets: Mapping[str, xr.Dataset],
                          numerics, report_dir, validation=None, readings=None,
                          products: Mapping[str, Product] = PAPER_PRODUCTS) -> str:
    """The reproduction report (Markdown), figures linked relative to ``report_dir``.

    ``figures`` maps product keys to image files; each figure of ``products`` that is given gets a
    section with its caption and the claims it carries. ``validation`` is the
    :class:`hubbeam.validation.report.Section` of the published-table validation (its summary
    sentence joins the report's summary), or None when the configuration has no ``validation``
    section. ``readings`` is the section of :func:`hubbeam.paper.explain.section` (None without a
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
    differing = [{"id": row["id"], "paper": number(row["paper"]), "computed": number(row["computed"]),
                  "unit": "" if row["unit"] == "1" else f" {row['unit']}"}
                 for row in claim_rows if row["verdict"] == "differs"]
    return render(
        "reproduction.md.j2", version=__version__, commits=", ".join(f"`{c}`" for c in commits),
        numerics={key: getattr(numerics, key) for key in ("rtol", "atol", "output_step", "quadrature_points")},
        claims=claim_rows, validation=validation, readings=readings, differing=differing,
        counts={v: sum(r["verdict"] == v for r in claim_rows) for v in ("agrees", "differs", "qualitative")},
        tables=[Path(tables[name]).read_text().strip() for name in sorted(tables)],
        figures=sections, all_claims=claims_markdown(claim_rows), runs=runs_markdown(datasets),
        readings_table=None if readings is None else readings_markdown(readings["readings"]))
