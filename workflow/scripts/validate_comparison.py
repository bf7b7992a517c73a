"""Snakemake shim: table and figure of the models against the Exudyn reference.

Runs :func:`hubbeam.pipeline.jobs.comparisons.validate_comparison` through the runner.
"""

from hubbeam.pipeline.jobs.comparisons import validate_comparison
from hubbeam.pipeline.runner import run

run(validate_comparison, snakemake)
