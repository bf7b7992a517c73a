"""Snakemake shim: frequencies of a non-uniform beam, Ritz vs our finite elements vs pyBModes.

Runs :func:`hubbeam.pipeline.jobs.eigen.validate_nonuniform` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import validate_nonuniform
from hubbeam.pipeline.runner import run

run(validate_nonuniform, snakemake)
