"""Snakemake shim: critical speeds over tip mass x position.

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_critical_speeds` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_critical_speeds
from hubbeam.pipeline.runner import run

run(eigen_critical_speeds, snakemake)
