"""Snakemake shim: draw one figure of a study: per case, per comparison or of the feedback designs.

Runs :func:`hubbeam.pipeline.jobs.figures.study_figure` through the runner.
"""

from hubbeam.pipeline.jobs.figures import study_figure
from hubbeam.pipeline.runner import run

run(study_figure, snakemake)
