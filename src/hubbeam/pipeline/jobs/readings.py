"""Jobs of the alternative readings of the paper (rules in ``readings.smk``; hubbeam.paper.readings):
one reading's claims, the claims x readings matrix."""

from __future__ import annotations

import logging

from hubbeam.paper.claims import read_claims
from hubbeam.paper.readings import evaluate_reading, matrix, read_rows, reading_rows, write_rows
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes

LOG = logging.getLogger(__name__)


def reading(job: Job) -> None:
    """The claims of one reading (``params.runs``, its :class:`hubbeam.paper.readings.ReadingRuns`)
    on the runs its change generates and the default runs (``input.datasets`` of ``params.cases``),
    beside the default claims (``input.claims``) -> ``output.csv``."""
    runs = job.params["runs"]
    simulations = dict(zip(job.params["cases"], job.input["datasets"]))
    rows, generated = evaluate_reading(runs, simulations, job.input["table2"], job.input["critical_speeds"])
    default = {row["id"]: row for row in read_claims(job.input["claims"])}
    with staged(job.output["csv"]) as (path,):
        write_rows(reading_rows(runs.name, rows, default), path)
    LOG.info("reading %s: generated runs %s", runs.name, ", ".join(generated) or "none (measure only)")
    for row in rows:
        LOG.info("%-12s %s: paper %s, computed %.6g", row["verdict"], row["id"], row["paper"], row["computed"])


def readings_matrix(job: Job) -> None:
    """Every reading's claim rows (``input.readings``) -> the matrix ``output.csv`` and ``output.nc``."""
    readings = job.params["readings"]
    rows = [row for path in job.input["readings"] for row in read_rows(path)]
    with staged(job.output["csv"]) as (csv,):
        write_rows(rows, csv)
    ds = matrix(rows, readings)
    ds.attrs = global_attributes("Claims of the paper under alternative readings", extra={"readings": readings})
    write_netcdf(ds, job.output["nc"])
    LOG.info("%d claim values under %d readings", len(rows), len(readings))
