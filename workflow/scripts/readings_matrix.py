"""Snakemake shim: the claims x readings matrix.

Runs :func:`hubbeam.pipeline.jobs.claims.readings_matrix` through the runner.
"""

from hubbeam.pipeline.jobs.claims import readings_matrix
from hubbeam.pipeline.runner import run

run(readings_matrix, snakemake)
