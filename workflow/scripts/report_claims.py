"""Snakemake shim: evaluate every claim of the paper against the results.

Runs :func:`hubbeam.pipeline.jobs.claims.claims` through the runner.
"""

from hubbeam.pipeline.jobs.claims import claims
from hubbeam.pipeline.runner import run

run(claims, snakemake)
