"""Snakemake shim: model-reference tip differences against the number of assumed modes.

Runs :func:`hubbeam.pipeline.jobs.validation.validate_modes` through the runner.
"""

from hubbeam.pipeline.jobs.validation import validate_modes
from hubbeam.pipeline.runner import run

run(validate_modes, snakemake)
