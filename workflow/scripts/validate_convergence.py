"""Snakemake shim: convergence of the Exudyn reference in elements, time step, Newton tolerance.

Runs :func:`hubbeam.pipeline.jobs.validation.validate_convergence` through the runner.
"""

from hubbeam.pipeline.jobs.validation import validate_convergence
from hubbeam.pipeline.runner import run

run(validate_convergence, snakemake)
