"""Snakemake shim: Markdown and LaTeX renderings of Table 2.

Runs :func:`hubbeam.pipeline.jobs.tables.table2_render` through the runner.
"""

from hubbeam.pipeline.jobs.tables import table2_render
from hubbeam.pipeline.runner import run

run(table2_render, snakemake)
