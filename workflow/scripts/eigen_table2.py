"""Snakemake shim: Table 2, natural and TLAM/FOAM frequencies beside the printed values.

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_table2` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_table2
from hubbeam.pipeline.runner import run

run(eigen_table2, snakemake)
