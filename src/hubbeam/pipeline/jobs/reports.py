"""Jobs of the reports (rules in ``report.smk``, ``study.smk`` and ``validate.smk``): the paper's
reproduction report, a study's report and summary, the report of the independent validation, and
the archive of a configuration's results."""

from __future__ import annotations

import csv
import logging
import os
from pathlib import Path

from hubbeam.control.cases import dataset_critical_speed, dataset_shaping_mode
from hubbeam.paper.claims import read_claims
from hubbeam.paper.explain import section
from hubbeam.paper.readings import read_rows
from hubbeam.paper.report import reproduction_markdown
from hubbeam.pipeline.runner import Job
from hubbeam.reporting.archive import build_archive, verify_archive
from hubbeam.reporting.document import markdown_to_html
from hubbeam.results.io import open_result, staged, write_netcdf, write_text
from hubbeam.study.controllers import controllers_markdown
from hubbeam.study.identification import identification_markdown
from hubbeam.study.plants import plant_row
from hubbeam.study.report import study_html, study_markdown
from hubbeam.study.shaping import reference_modes, shaped_runs, shaping_dataset
from hubbeam.study.shaping_report import shaping_section
from hubbeam.study.summary import COLUMNS, case_summary
from hubbeam.study.trust import design_table
from hubbeam.validation.report import published_section, validation_markdown

LOG = logging.getLogger(__name__)


def reproduction_report(job: Job) -> None:
    """The reproduction report, Markdown and self-contained HTML: the claims, the figures and
    tables, the runs, and, when the rule has those inputs, the published-table validation and the
    claims under alternative readings."""
    inputs, p = job.input, job.params
    out = Path(job.output["markdown"])
    figures = {Path(path).stem: path for path in inputs["figures"]}
    table_files = {Path(path).stem: path for path in inputs["tables"]}
    datasets = {case: open_result(path) for case, path in zip(p["cases"], inputs["datasets"])}
    validation = None
    if "published" in inputs:
        validation = published_section(inputs["published"], inputs["tip_mass"], inputs["curves"],
                                       inputs["published_figure"], out.parent)
    claim_rows = read_claims(inputs["claims"])
    readings = section(claim_rows, read_rows(inputs["readings"]), p["readings"]) if "readings" in inputs else None
    text = reproduction_markdown(claim_rows, figures, table_files, datasets, p["numerics"], out.parent,
                                 validation=validation, readings=readings)
    write_text(out, text)
    write_text(job.output["html"], markdown_to_html(text, out.parent))
    LOG.info("%s: %d figures, %d tables, %d runs, validation: %s", out, len(figures), len(table_files), len(datasets),
             validation.summary if validation else "not configured")


def study_report(job: Job) -> None:
    """A study's report (Markdown, HTML) and its summary.csv, a row per case (``input.simulations``
    of ``params.cases``); its plants (``input.plants``, each plant's dataset); its figures by section
    of the report (``params.figures``); its identification (:func:`_identification`). With
    an output ``shaping`` (a study that shapes commands), the section and the numbers of
    :mod:`hubbeam.study.shaping`, on the reference model's modes from the linear models."""
    p, out = job.params, job.output
    report_dir = Path(out["markdown"]).parent
    datasets = {case: open_result(path) for case, path in zip(p["cases"], job.input["simulations"])}
    rows = [case_summary(case, ds) for case, ds in datasets.items()]
    plants = [plant_row(open_result(path)) for path in job.input.get("plants", ())]
    figures = {name: {label: os.path.relpath(path, report_dir) for label, path in shown.items()}
               for name, shown in p["figures"].items()}
    shaping = None
    if "shaping" in out:  # a study that shapes commands (its plan)
        runs = shaped_runs(datasets)
        modes = reference_modes(datasets, dataset_shaping_mode)
        critical = dataset_critical_speed(next(iter(datasets.values())), "TLAM")
        shaping = shaping_section(runs, modes, critical)
    markdown = study_markdown(p["study"], p["beam"], rows, figures, designs=design_table(datasets),
                              plants=plants, shaping=shaping,
                              controllers=_controllers(job, datasets, figures, report_dir),
                              identification=_identification(job, report_dir))
    write_text(out["markdown"], markdown)
    write_text(out["html"], study_html(markdown, p["study"].title or p["study"].name, report_dir))
    with staged(out["summary"]) as (summary,), open(summary, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    if "shaping" in out:
        write_netcdf(shaping_dataset(runs, modes, critical), out["shaping"])
    LOG.info("%d cases -> %s, %s, %s", len(rows), out["markdown"], out["html"], out["summary"])


def _identification(job: Job, report_dir: Path) -> str:
    """The report's section on the ``identify`` section from the rule's optional inputs: the fit
    (``identification``), the fitted plant (``identification_fitted``) and the fit's figures
    (``identification_figures``, PNG); empty without them."""
    inputs = job.input
    if "identification" not in inputs:
        return ""
    figures = {Path(path).stem: os.path.relpath(path, report_dir) for path in inputs["identification_figures"]}
    return identification_markdown(open_result(inputs["identification"]), figures,
                                   job.params["identification_applied"],
                                   os.path.relpath(inputs["identification_fitted"], report_dir))


def _controllers(job: Job, datasets, figures, report_dir: Path) -> str:
    """The report's section on sampled controllers from the rule's optional inputs: the sample-time
    sweep (``sample_time``), the robustness maps (``robustness``) and the exported controllers
    (``controllers``: ``.mat`` and ``.json`` per case of ``params.control_cases``, in that order)."""
    inputs = job.input
    files = [os.path.relpath(path, report_dir) for path in inputs.get("controllers", ())]
    exports = {case: (files[2 * k], files[2 * k + 1]) for k, case in enumerate(job.params.get("control_cases", ()))}
    shown = {key: path for section in figures.values() for key, path in section.items()}
    return controllers_markdown(datasets, open_result(inputs["sample_time"]) if "sample_time" in inputs else None,
                                open_result(inputs["robustness"]) if "robustness" in inputs else None, exports, shown)


def validation_report(job: Job) -> None:
    """The report of ``snakemake validate``, Markdown and HTML: the non-uniform checks and, with the
    inputs of the Exudyn comparison, that comparison."""
    inputs = job.input
    out = Path(job.output["markdown"])
    exudyn = ({key: inputs[key] for key in ("comparison", "mode_study", "convergence", "figure")}
              if "comparison" in inputs else None)
    text = validation_markdown(out.parent, inputs["ritz_fe"], inputs.get("pybmodes"), exudyn)
    write_text(out, text)
    write_text(job.output["html"],
               markdown_to_html(text, out.parent, title="hubbeam validation against independent models"))
    LOG.info("%s: written from %s", out, ", ".join(str(inputs[key]) for key in inputs if key != "code"))


def archive(job: Job) -> None:
    """The archive of the configuration's results (``input.files``) with the workflow and the
    configuration (``params.config``), named inside it relative to its results folder
    (``params.paths``: the archive's top folder and root), then checked against its manifest."""
    paths = job.params["paths"]
    files = job.input["files"]
    written = build_archive([os.path.relpath(path, paths.archive_root) for path in files], job.params["config"],
                            job.output["archive"], workflow_root=job.params["workflow_root"],
                            root=paths.archive_root, top=paths.archive_top)
    problems = verify_archive(written, paths.archive_top)
    LOG.info("%s: %d files + workflow + config + crate + manifest; verification: %s", written, len(files),
             problems or "ok")
    if problems:
        raise RuntimeError(f"{written} does not verify: {problems}")
