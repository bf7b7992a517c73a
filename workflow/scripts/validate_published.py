"""Snakemake shim: rotating-cantilever frequencies against the published tables, and their figure.

Runs :func:`hubbeam.pipeline.jobs.figures.validate_published` through the runner.
"""

from hubbeam.pipeline.jobs.figures import validate_published
from hubbeam.pipeline.runner import run

run(validate_published, snakemake)
