"""Jobs that draw (rules in ``figures.smk``, ``study.smk`` and ``sweeps.smk``): the figures of the
registry's products (hubbeam.reporting.products) and the sweep maps. Every figure is written as
PDF with its PNG beside it (:func:`hubbeam.plotting.draw`), both by rename once complete."""

from __future__ import annotations

import logging
from pathlib import Path

from hubbeam.pipeline.runner import Job
from hubbeam.plotting import draw, render_files
from hubbeam.plotting.sweep_maps import plot as sweep_map
from hubbeam.reporting.products import resolve
from hubbeam.results.io import open_result, staged

LOG = logging.getLogger(__name__)
#: the inputs of a figure's rule that are not the result files it draws
NOT_DRAWN = ("style", "code")


def _figure_files(job: Job) -> list[Path]:
    """The PDF of ``output.pdf`` and the PNG beside it."""
    pdf = Path(job.output["pdf"])
    return [pdf, pdf.with_suffix(".png")]


def simulation_figure(job: Job) -> None:
    """A figure drawn from simulation runs (``input.datasets`` of ``params.cases``) by the product's
    function ``params.function``."""
    written = _figure_files(job)
    with staged(*written) as (pdf, _png):  # save_figure writes the PNG beside the PDF
        render_files(resolve(job.params["function"]), dict(zip(job.params["cases"], job.input["datasets"])), pdf)
    LOG.info("%s: cases %s -> %s", job.params["function"], ", ".join(job.params["cases"]),
             ", ".join(map(str, written)))


def files_figure(job: Job) -> None:
    """A figure drawn from the result files it names: the named inputs but ``style`` and ``code``
    are opened and passed to the product's function (``params.function``) under their names, with
    the product's ``params.options`` (e.g. the tip mass a linear-model figure shows)."""
    files = {name: path for name, path in job.input.items() if name not in NOT_DRAWN}
    datasets = {name: open_result(path) for name, path in files.items()}
    written = _figure_files(job)
    with staged(*written) as (pdf, _png):
        draw(resolve(job.params["function"]), pdf, **datasets, **job.params["options"])
    LOG.info("%s(%s) -> %s", job.params["function"], files, ", ".join(map(str, written)))


def study_figure(job: Job) -> None:
    """A study's figure of simulations (``input.simulations`` of ``params.cases``), drawn by the
    product's function with the figure's name: per case (one run, passed alone), per comparison or
    of the feedback designs (the runs by case name)."""
    p = job.params
    datasets = {case: open_result(path) for case, path in zip(p["cases"], job.input["simulations"])}
    data = next(iter(datasets.values())) if p["per_case"] else datasets
    written = _figure_files(job)
    with staged(*written) as (pdf, _png):
        draw(resolve(p["function"]), pdf, p["name"], data)
    LOG.info("%s(%r, %s) -> %s", p["function"], p["name"], ", ".join(datasets), ", ".join(map(str, written)))


def figure_sweep(job: Job) -> None:
    """The map of a parameter sweep (``input.sweep``) as configured in its ``figure``."""
    written = _figure_files(job)
    with staged(*written) as (pdf, _png):
        draw(sweep_map, pdf, open_result(job.input["sweep"]))
    LOG.info("sweep map %s -> %s", job.input["sweep"], ", ".join(map(str, written)))
