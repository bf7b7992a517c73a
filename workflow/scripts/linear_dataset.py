"""Snakemake shim: one dataset of the linear models (Campbell diagram, poles and zeros, Bode).

Runs :func:`hubbeam.pipeline.jobs.linear.linear_dataset` through the runner.
"""

from hubbeam.pipeline.jobs.linear import linear_dataset
from hubbeam.pipeline.runner import run

run(linear_dataset, snakemake)
