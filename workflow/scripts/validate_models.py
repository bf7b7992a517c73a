"""Snakemake shim: tip outputs of the hubbeam models for one validation case.

Runs :func:`hubbeam.pipeline.jobs.validation.validate_models` through the runner.
"""

from hubbeam.pipeline.jobs.validation import validate_models
from hubbeam.pipeline.runner import run

run(validate_models, snakemake)
