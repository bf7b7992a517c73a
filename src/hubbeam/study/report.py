"""The study report: Markdown from the template ``reporting/templates/study_report.md.j2``, HTML from the
Markdown (``hubbeam.reporting.document``).

:func:`study_markdown` summarises the study's beam in a few rows (:func:`beam_summary`; the full
table of stations stays in the archived configuration) beside the figure of its properties, lists
a row per case (:mod:`hubbeam.study.summary`) with links to its figure, the comparison figures,
the LQR designs tried on another model (:mod:`hubbeam.study.trust`: a table, the verdict per
design model and their figure), the eigen-analysis figures (the beam's mode shapes among them) and
the linear models' figures: each figure in the section its product names in the registry
(:mod:`hubbeam.reporting.products`). Paths of figures are given relative to the report's folder,
so the Markdown reads the same in the results archive. :func:`study_html` renders it into one
self-contained page (figures embedded).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from hubbeam.model.beam import SECTION_PROPERTIES, SECTION_UNITS, beam_config
from hubbeam.reporting.document import markdown_table, markdown_to_html, render
from hubbeam.reporting.formatting import number
from hubbeam.reporting.products import (
    BEAM_SECTION,
    CASES_SECTION,
    COMPARISONS_SECTION,
    DESIGNS_SECTION,
    EIGEN_SECTION,
    LINEAR_SECTION,
    PLANTS_SECTION,
    SHAPING_SECTION,
)
from hubbeam.study.plants import plants_markdown
from hubbeam.study.summary import NO_SHAPER
from hubbeam.study.trust import REFERENCE_MODEL, SETTLING_BAND, TRUST_TOLERANCE, performance, verdicts


def study_markdown(study, beam, rows: Sequence[Mapping],
                   figures: Mapping[str, Mapping[str, str]], designs: Sequence[Mapping] = (),
                   plants: Sequence[Mapping] = (), controllers: str = "",
                   shaping: Mapping | None = None, identification: str = "") -> str:
    """The report in Markdown of the study ``study`` (its record: name, title, description) and its
    beam (a beam record). ``rows`` are summary rows, ``designs`` the rows of
    :func:`hubbeam.study.trust.design_table`, ``plants`` those of
    :func:`hubbeam.study.plants.plant_row`; ``figures`` gives, per section of the report (the
    products' ``section``, :data:`hubbeam.reporting.products.SECTIONS`), the PNG paths relative
    to the report by label: the case of a figure per case, the comparison of a figure per
    comparison, the figure's name otherwise. Sections the study report has no place for (the
    paper's) are left out. ``controllers``: the section on sampled controllers
    (:func:`hubbeam.study.controllers.controllers_markdown`), shown before the case figures;
    ``shaping``: the section of a command-shaping study (:func:`hubbeam.study.shaping_report.shaping_section`),
    None without one; ``identification``: the section of the fit to a rig's experiments
    (:func:`hubbeam.study.identification.identification_markdown`), shown before the cases."""
    def first(section: str) -> str | None:
        return next(iter(figures.get(section, {}).values()), None)

    return render("study_report.md.j2", study=study, beam=beam_config(beam), rows=rows,
                  beam_table=beam_markdown(beam), cases_table=cases_markdown(rows),
                  plants_table=plants_markdown(plants) if plants else "",
                  plant_figures=_by_plant(figures.get(PLANTS_SECTION, {})),
                  case_figures=figures.get(CASES_SECTION, {}),
                  comparison_figures=figures.get(COMPARISONS_SECTION, {}),
                  beam_figure=first(BEAM_SECTION),
                  designs_table=designs_markdown(designs) if designs else "",
                  verdicts=verdicts(list(designs)), performance=performance(list(designs)),
                  design_figure=first(DESIGNS_SECTION),
                  reference_model=REFERENCE_MODEL, settling_band=SETTLING_BAND,
                  trust_tolerance=TRUST_TOLERANCE,
                  eigen_figures=figures.get(EIGEN_SECTION, {}), linear_figures=figures.get(LINEAR_SECTION, {}),
                  controllers=controllers, identification=identification,
                  shaping=shaping, shaping_figures=figures.get(SHAPING_SECTION, {}))


def _by_plant(figures: Mapping[str, str]) -> dict[str, dict[str, str]]:
    """The plants' figures (labelled ``<plant>/<product>``) by plant, then by product."""
    grouped: dict[str, dict[str, str]] = {}
    for label, path in figures.items():
        plant, _, product = label.partition("/")
        grouped.setdefault(plant, {})[product] = path
    return grouped


def beam_summary(params) -> list[dict]:
    """One row per property of the beam (uniform or by sections): ``name``, ``unit``, its value at
    the ``root`` and the ``tip``, and its ``min`` and ``max`` over the stations."""
    stations = params.stations
    rows = []
    for name in SECTION_PROPERTIES:
        values = getattr(params, f"{name}_at")(stations)
        rows.append({"name": name, "unit": SECTION_UNITS[name], "root": float(values[0]), "tip": float(values[-1]),
                     "min": float(values.min()), "max": float(values.max())})
    return rows


def beam_markdown(beam) -> str:
    """The beam in a few rows (:func:`beam_summary`): one per property, whatever its stations."""
    return markdown_table(("property", "unit", "at the root", "at the tip", "min", "max"),
                          ([row["name"], row["unit"], number(row["root"]), number(row["tip"]),
                            number(row["min"]), number(row["max"])] for row in beam_summary(beam)))


def cases_markdown(rows: Sequence[Mapping]) -> str:
    """A line per case: settings, peak and residual tip deflection, validity, convergence check;
    with shaped runs among them, the shaper and its move-time penalty too."""
    def convergence(row):
        if row["convergence"] == "not checked":
            return row["convergence"]
        return (f"{row['convergence']} (tolerance {number(row['convergence_tolerance_diff_m'], 2)} m, "
                f"modes {number(row['convergence_modes_diff_m'], 2)} m)")

    shaped = any(row["shaper"] != NO_SHAPER for row in rows)

    def shaping(row):
        return [row["shaper"], number(row["move_time_penalty_s"])] if shaped else []

    return markdown_table(
        ("case", "model", "maneuver", "modes", "tip mass (kg)", "peak v(L) (m)", "at t (s)", "end (s)",
         *(("shaper", "move-time penalty (s)") if shaped else ()), "residual (m)", "validity", "convergence check"),
        ([row["case"], row["model"], row["maneuver"], row["modes"], number(row["tip_mass_kg"]),
          number(row["peak_tip_deflection_m"]), number(row["peak_time_s"]), number(row["maneuver_end_s"]),
          *shaping(row), number(row["residual_amplitude_m"]), row["validity"], convergence(row)] for row in rows))


def designs_markdown(designs: Sequence[Mapping]) -> str:
    """A line per LQR design and the model it ran on: its measures, stability and the gap."""
    def cells(run):
        if run is None:
            return ["not run"] + [""] * 4
        if not run["stable"]:
            return ["unstable"] + [""] * 4
        return ["stable", number(run["peak_tip_deflection_m"], 3), number(run["residual_vibration_m"], 3),
                number(run["settling_time_s"], 3), number(run["peak_torque_Nm"], 3)]

    lines = []
    for row in designs:
        for which in ("own", "reference"):
            run = row[which]
            ran_on = run["model"] if run else (row["design_model"] if which == "own" else REFERENCE_MODEL)
            gap = number(100 * row["gap"], 2) if which == "reference" and row["gap"] == row["gap"] else ""
            verdict = ({True: "good enough", False: "not good enough", None: "not judged (no prediction)"}[row["good"]]
                       if which == "reference" else "")
            lines.append([row["design_model"], number(row["design_speed"]), ran_on, *cells(run), gap, verdict])
    return markdown_table(("designed on", "at (rad/s)", "run on", "loop", "peak v(L) (m)", "residual (m)",
                           "settling (s)", "peak torque (N m)", "gap (%)", "verdict"), lines)


def study_html(markdown: str, title: str, report_dir) -> str:
    """The Markdown report as one HTML page; figure paths are relative to ``report_dir``."""
    return markdown_to_html(markdown, report_dir, title=title)
