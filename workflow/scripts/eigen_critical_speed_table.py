"""Snakemake shim: critical speed of each tip mass at the beam tip, the table the claims read.

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_critical_speed_table` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_critical_speed_table
from hubbeam.pipeline.runner import run

run(eigen_critical_speed_table, snakemake)
