"""Snakemake shim: frequencies of a non-uniform beam, Ritz vs our finite elements vs pyBModes.

Runs :func:`hubbeam.pipeline.jobs.nonuniform.validate_nonuniform` through the runner.
"""

from hubbeam.pipeline.jobs.nonuniform import validate_nonuniform
from hubbeam.pipeline.runner import run

run(validate_nonuniform, snakemake)
