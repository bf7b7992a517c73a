"""Snakemake shim: the implementation files (.mat, .json) of every sampled controller.

Runs :func:`hubbeam.pipeline.jobs.control.control_export` through the runner.
"""

from hubbeam.pipeline.jobs.control import control_export
from hubbeam.pipeline.runner import run

run(control_export, snakemake)
