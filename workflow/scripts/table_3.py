"""Snakemake shim: Table 3 (largest |Q_theta| per torque amplitude, FOAM), csv + md + tex.

Runs :func:`hubbeam.pipeline.jobs.tables.table3` through the runner.
"""

from hubbeam.pipeline.jobs.tables import table3
from hubbeam.pipeline.runner import run

run(table3, snakemake)
