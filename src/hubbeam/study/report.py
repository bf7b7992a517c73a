"""The study report: Markdown from a Jinja2 template, HTML from the Markdown (markdown-it-py).

:func:`study_markdown` lists the study's beam, a row per case (:mod:`hubbeam.study.summary`)
with links to its figure, the comparison figures and the eigen-analysis figures; paths of
figures are given relative to the report's folder, so the report reads the same in the results
archive. :func:`study_html` renders that Markdown into a stand-alone page.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import jinja2
from markdown_it import MarkdownIt

from hubbeam.study.summary import COLUMNS

TEMPLATES = jinja2.Environment(
    loader=jinja2.FileSystemLoader(Path(__file__).with_name("templates")),
    autoescape=jinja2.select_autoescape(enabled_extensions=("html.j2",), default_for_string=False),
    keep_trailing_newline=True, trim_blocks=True, lstrip_blocks=True, undefined=jinja2.StrictUndefined,
)


def number(value, digits: int = 4) -> str:
    """A table cell: ``-`` for NaN, ``yes``/``no`` for flags, ``digits`` significant figures."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "-" if math.isnan(value) else f"{value:.{digits}g}"
    return str(value)


TEMPLATES.filters["number"] = number


def study_markdown(study: Mapping, beam: Mapping, rows: Sequence[Mapping],
                   case_figures: Mapping[str, str], comparison_figures: Mapping[str, str],
                   eigen_figures: Mapping[str, str]) -> str:
    """The report in Markdown. ``rows`` are summary rows; the figure maps give, per case,
    comparison or eigen figure, the PNG path relative to the report."""
    return TEMPLATES.get_template("report.md.j2").render(
        study=study, beam=beam, rows=rows, columns=COLUMNS, case_figures=case_figures,
        comparison_figures=comparison_figures, eigen_figures=eigen_figures)


def study_html(markdown: str, title: str) -> str:
    """A stand-alone HTML page of the Markdown report (tables enabled)."""
    body = MarkdownIt("commonmark").enable("table").render(markdown)
    return TEMPLATES.get_template("report.html.j2").render(title=title, body=body)
