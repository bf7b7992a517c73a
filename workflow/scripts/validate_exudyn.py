"""Snakemake shim: one prescribed spin-up of the Exudyn ANCF reference.

Runs :func:`hubbeam.pipeline.jobs.reference.validate_exudyn` through the runner.
"""

from hubbeam.pipeline.jobs.reference import validate_exudyn
from hubbeam.pipeline.runner import run

run(validate_exudyn, snakemake)
