"""The study report: Markdown from the template ``templates/study_report.md.j2``, HTML from the
Markdown (``hubbeam.document``).

:func:`study_markdown` lists the study's beam, a row per case (:mod:`hubbeam.study.summary`)
with links to its figure, the comparison figures and the eigen-analysis figures; paths of
figures are given relative to the report's folder, so the Markdown reads the same in the results
archive. :func:`study_html` renders it into one self-contained page (figures embedded).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from hubbeam.document import markdown_table, markdown_to_html, render
from hubbeam.formatting import number


def study_markdown(study: Mapping, beam: Mapping, rows: Sequence[Mapping],
                   case_figures: Mapping[str, str], comparison_figures: Mapping[str, str],
                   eigen_figures: Mapping[str, str]) -> str:
    """The report in Markdown. ``rows`` are summary rows; the figure maps give, per case,
    comparison or eigen figure, the PNG path relative to the report."""
    return render("study_report.md.j2", study=study, beam=beam, rows=rows,
                  beam_table=beam_markdown(beam), cases_table=cases_markdown(rows),
                  case_figures=case_figures, comparison_figures=comparison_figures,
                  eigen_figures=eigen_figures)


#: the columns of a uniform beam's table, given by its material and section (title, key of ``beam``)
UNIFORM_BEAM = (("length (m)", "length"), ("density (kg m-3)", "density"), ("area (m2)", "area"),
                ("E (N m-2)", "youngs_modulus"), ("I (m4)", "second_moment"),
                ("hub inertia (kg m2)", "hub_inertia"), ("hub radius (m)", "hub_radius"))
#: the same, for a uniform beam given by its products ``rhoA``, ``EI``, ``EA``
UNIFORM_BEAM_PRODUCTS = (("length (m)", "length"), ("rhoA (kg m-1)", "rhoA"), ("EI (N m2)", "EI"),
                         ("EA (N)", "EA"), ("hub inertia (kg m2)", "hub_inertia"),
                         ("hub radius (m)", "hub_radius"))


def beam_markdown(beam: Mapping) -> str:
    """The beam of the study: its stations (``beam.sections``) or its uniform properties."""
    if "sections" in beam:
        sections = beam["sections"]
        return markdown_table(("x (m)", "rhoA (kg m-1)", "EI (N m2)", "EA (N)"),
                              zip(*(map(number, sections[key]) for key in ("x", "rhoA", "EI", "EA"))))
    columns = UNIFORM_BEAM_PRODUCTS if "rhoA" in beam else UNIFORM_BEAM
    return markdown_table([title for title, _ in columns], [[number(beam[key]) for _, key in columns]])


def cases_markdown(rows: Sequence[Mapping]) -> str:
    """A line per case: settings, peak and residual tip deflection, validity, convergence check."""
    def convergence(row):
        if row["convergence"] == "not checked":
            return row["convergence"]
        return (f"{row['convergence']} (tolerance {number(row['convergence_tolerance_diff_m'], 2)} m, "
                f"modes {number(row['convergence_modes_diff_m'], 2)} m)")

    return markdown_table(
        ("case", "model", "maneuver", "modes", "tip mass (kg)", "peak v(L) (m)", "at t (s)", "end (s)",
         "residual (m)", "validity", "convergence check"),
        ([row["case"], row["model"], row["maneuver"], row["modes"], number(row["tip_mass_kg"]),
          number(row["peak_tip_deflection_m"]), number(row["peak_time_s"]), number(row["maneuver_end_s"]),
          number(row["residual_amplitude_m"]), row["validity"], convergence(row)] for row in rows))


def study_html(markdown: str, title: str, report_dir) -> str:
    """The Markdown report as one HTML page; figure paths are relative to ``report_dir``."""
    return markdown_to_html(markdown, report_dir, title=title)
