"""Snakemake shim: draw the map of a parameter sweep.

Runs :func:`hubbeam.pipeline.jobs.figures.figure_sweep` through the runner.
"""

from hubbeam.pipeline.jobs.figures import figure_sweep
from hubbeam.pipeline.runner import run

run(figure_sweep, snakemake)
