"""Snakemake shim: Exudyn reference and model tip deflections of one case, with differences.

Runs :func:`hubbeam.pipeline.jobs.validation.validate_case` through the runner.
"""

from hubbeam.pipeline.jobs.validation import validate_case
from hubbeam.pipeline.runner import run

run(validate_case, snakemake)
