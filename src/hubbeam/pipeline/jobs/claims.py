"""Jobs of the paper's claims (rules ``claims`` in ``report.smk`` and those of ``readings.smk``;
hubbeam.paper.claims, hubbeam.paper.readings): every claim against the results, one alternative
reading's claims, the claims x readings matrix. Together because they import the same modules."""

from __future__ import annotations

import logging
from collections import Counter

from hubbeam.paper.claims import Results, evaluate, read_claims, write_claims
from hubbeam.paper.readings import evaluate_reading, matrix, read_rows, reading_rows, write_rows
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes

LOG = logging.getLogger(__name__)


def claims(job: Job) -> None:
    """Every claim of the paper against the runs (``input.datasets`` of ``params.cases``) and the
    eigen-analysis tables -> ``output.claims``."""
    results = Results(dict(zip(job.params["cases"], job.input["datasets"])), table2_csv=job.input["table2"],
                      critical_speeds_csv=job.input["critical_speeds"])
    rows = evaluate(results)
    with staged(job.output["claims"]) as (path,):
        write_claims(rows, path)
    LOG.info("%d claims: %s", len(rows), dict(Counter(row["verdict"] for row in rows)))
    for row in rows:
        LOG.info("%-12s %s: paper %s, computed %.6g", row["verdict"], row["id"], row["paper"], row["computed"])


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
    ds.attrs = global_attributes("Claims of the paper under alternative readings",
                                 extra={"readings": {name: reading.to_dict() for name, reading in readings.items()}})
    write_netcdf(ds, job.output["nc"])
    LOG.info("%d claim values under %d readings", len(rows), len(readings))
