"""Snakemake shim: rotating-cantilever frequencies against the published tables, and their figure.

Runs :func:`hubbeam.pipeline.jobs.comparisons.validate_published` through the runner.
"""

from hubbeam.pipeline.jobs.comparisons import validate_published
from hubbeam.pipeline.runner import run

run(validate_published, snakemake)
