"""Snakemake shim: a study's report (Markdown, HTML) and its summary.csv.

Runs :func:`hubbeam.pipeline.jobs.reports.study_report` through the runner.
"""

from hubbeam.pipeline.jobs.reports import study_report
from hubbeam.pipeline.runner import run

run(study_report, snakemake)
