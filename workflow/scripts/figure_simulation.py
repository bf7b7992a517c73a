"""Snakemake shim: draw one figure of simulation runs (the product's function).

Runs :func:`hubbeam.pipeline.jobs.figures.simulation_figure` through the runner.
"""

from hubbeam.pipeline.jobs.figures import simulation_figure
from hubbeam.pipeline.runner import run

run(simulation_figure, snakemake)
