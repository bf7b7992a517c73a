"""Snakemake shim: the first vibration mode shapes of the linear models along the span.

Runs :func:`hubbeam.pipeline.jobs.linear.linear_mode_shapes` through the runner.
"""

from hubbeam.pipeline.jobs.linear import linear_mode_shapes
from hubbeam.pipeline.runner import run

run(linear_mode_shapes, snakemake)
