"""Snakemake shim: draw one figure of the result files it names (eigen-analysis, linear models).

Runs :func:`hubbeam.pipeline.jobs.figures.files_figure` through the runner.
"""

from hubbeam.pipeline.jobs.figures import files_figure
from hubbeam.pipeline.runner import run

run(files_figure, snakemake)
