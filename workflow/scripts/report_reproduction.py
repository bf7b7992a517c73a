"""Snakemake shim: the reproduction report (Markdown and self-contained HTML).

Runs :func:`hubbeam.pipeline.jobs.reports.reproduction_report` through the runner.
"""

from hubbeam.pipeline.jobs.reports import reproduction_report
from hubbeam.pipeline.runner import run

run(reproduction_report, snakemake)
