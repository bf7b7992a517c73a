"""Snakemake shim: join the chunks of a parameter sweep into its map.

Runs :func:`hubbeam.pipeline.jobs.sweeps.sweep` through the runner.
"""

from hubbeam.pipeline.jobs.sweeps import sweep
from hubbeam.pipeline.runner import run

run(sweep, snakemake)
