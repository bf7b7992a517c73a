"""The study report: Markdown from the template ``templates/study_report.md.j2``, HTML from the
Markdown (``hubbeam.document``).

:func:`study_markdown` lists the study's beam, a row per case (:mod:`hubbeam.study.summary`)
with links to its figure, the comparison figures and the eigen-analysis figures; paths of
figures are given relative to the report's folder, so the Markdown reads the same in the results
archive. :func:`study_html` renders it into one self-contained page (figures embedded).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from hubbeam.document import markdown_to_html, render
from hubbeam.study.summary import COLUMNS


def study_markdown(study: Mapping, beam: Mapping, rows: Sequence[Mapping],
                   case_figures: Mapping[str, str], comparison_figures: Mapping[str, str],
                   eigen_figures: Mapping[str, str]) -> str:
    """The report in Markdown. ``rows`` are summary rows; the figure maps give, per case,
    comparison or eigen figure, the PNG path relative to the report."""
    return render("study_report.md.j2", study=study, beam=beam, rows=rows, columns=COLUMNS,
                  case_figures=case_figures, comparison_figures=comparison_figures,
                  eigen_figures=eigen_figures)


def study_html(markdown: str, title: str, report_dir) -> str:
    """The Markdown report as one HTML page; figure paths are relative to ``report_dir``."""
    return markdown_to_html(markdown, report_dir, title=title)
