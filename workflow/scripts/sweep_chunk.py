"""Snakemake shim: simulate one chunk of a parameter sweep.

Runs :func:`hubbeam.pipeline.jobs.sweeps.sweep_chunk` through the runner.
"""

from hubbeam.pipeline.jobs.sweeps import sweep_chunk
from hubbeam.pipeline.runner import run

run(sweep_chunk, snakemake)
