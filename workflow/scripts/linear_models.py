"""Snakemake shim: the linear models of every model and hub condition as netCDF and MATLAB files.

Runs :func:`hubbeam.pipeline.jobs.linear.linear_models` through the runner.
"""

from hubbeam.pipeline.jobs.linear import linear_models
from hubbeam.pipeline.runner import run

run(linear_models, snakemake)
