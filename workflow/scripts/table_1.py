"""Snakemake shim: Table 1 (physical parameters), csv + md + tex.

Runs :func:`hubbeam.pipeline.jobs.tables.table1` through the runner.
"""

from hubbeam.pipeline.jobs.tables import table1
from hubbeam.pipeline.runner import run

run(table1, snakemake)
