"""Snakemake shim: Table 3 (largest |Q_theta| per torque amplitude, FOAM), csv + md + tex.

Runs :func:`hubbeam.pipeline.jobs.reports.table3` through the runner.
"""

from hubbeam.pipeline.jobs.reports import table3
from hubbeam.pipeline.runner import run

run(table3, snakemake)
