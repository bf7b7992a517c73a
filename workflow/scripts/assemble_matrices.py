"""Snakemake shim: the system matrices of one tip-mass configuration.

Runs :func:`hubbeam.pipeline.jobs.simulation.matrices` through the runner.
"""

from hubbeam.pipeline.jobs.simulation import matrices
from hubbeam.pipeline.runner import run

run(matrices, snakemake)
