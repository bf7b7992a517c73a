"""Snakemake shim: the report of `snakemake validate`, Markdown and HTML.

Runs :func:`hubbeam.pipeline.jobs.reports.validation_report` through the runner.
"""

from hubbeam.pipeline.jobs.reports import validation_report
from hubbeam.pipeline.runner import run

run(validation_report, snakemake)
