"""Snakemake shim: Campbell diagram, TLAM and FOAM frequencies against hub speed.

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_campbell` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_campbell
from hubbeam.pipeline.runner import run

run(eigen_campbell, snakemake)
