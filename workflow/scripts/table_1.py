"""Snakemake shim: Table 1 (physical parameters), csv + md + tex.

Runs :func:`hubbeam.pipeline.jobs.reports.table1` through the runner.
"""

from hubbeam.pipeline.jobs.reports import table1
from hubbeam.pipeline.runner import run

run(table1, snakemake)
