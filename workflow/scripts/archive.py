"""Snakemake shim: bundle the results into one .tar.gz with a SHA-256 manifest and an RO-Crate.

Runs :func:`hubbeam.pipeline.jobs.reports.archive` through the runner.
"""

from hubbeam.pipeline.jobs.reports import archive
from hubbeam.pipeline.runner import run

run(archive, snakemake)
