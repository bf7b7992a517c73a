"""Jobs of Tables 1-3 of the paper (rules in ``figures.smk``), each written as csv, Markdown and
LaTeX (:mod:`hubbeam.paper.tables`)."""

from __future__ import annotations

import logging

from hubbeam.paper import tables
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, staged

LOG = logging.getLogger(__name__)


def _write_table(job: Job, table) -> None:
    """Write ``table`` as ``output.csv``, ``output.md`` and ``output.tex``."""
    out = job.output
    with staged(out["csv"], out["md"], out["tex"]) as (csv_file, _md, _tex):
        tables.write_table(table, csv_file)
    LOG.info("%s", tables.to_markdown(table))


def table1(job: Job) -> None:
    """Table 1, the physical parameters of ``params.beam`` beside the printed ones."""
    _write_table(job, tables.table1(job.params["beam"]))


def table2_render(job: Job) -> None:
    """The Markdown and LaTeX renderings of Table 2 (its csv, ``input.csv``, comes from the eigen-analysis)."""
    table = tables.table2(job.input["csv"], job.params["speed"])
    with staged(job.output["md"], job.output["tex"]) as (md, _tex):
        tables.write_table(table, md.with_suffix(".csv"), csv=False)  # .md and .tex beside that name
    LOG.info("%s", tables.to_markdown(table))


def table3(job: Job) -> None:
    """Table 3, the largest |Q_theta| per torque amplitude (FOAM), from the runs ``input.datasets``
    of ``params.cases``."""
    runs = zip(job.params["cases"], job.input["datasets"])
    _write_table(job, tables.table3({case: open_result(path) for case, path in runs}))
