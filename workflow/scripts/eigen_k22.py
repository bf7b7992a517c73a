"""Snakemake shim: eigenvalues of K22 over tip mass x position x speed (Fig. 9).

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_k22` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_k22
from hubbeam.pipeline.runner import run

run(eigen_k22, snakemake)
