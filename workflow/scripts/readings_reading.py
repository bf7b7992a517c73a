"""Snakemake shim: the claims of one alternative reading of the paper.

Runs :func:`hubbeam.pipeline.jobs.claims.reading` through the runner.
"""

from hubbeam.pipeline.jobs.claims import reading
from hubbeam.pipeline.runner import run

run(reading, snakemake)
