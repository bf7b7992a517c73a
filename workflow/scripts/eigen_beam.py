"""Snakemake shim: the beam as data: its properties along the span and its first mode shapes.

Runs :func:`hubbeam.pipeline.jobs.eigen.eigen_beam` through the runner.
"""

from hubbeam.pipeline.jobs.eigen import eigen_beam
from hubbeam.pipeline.runner import run

run(eigen_beam, snakemake)
