"""Snakemake shim: simulate one case.

Runs :func:`hubbeam.pipeline.jobs.simulation.simulate` through the runner.
"""

from hubbeam.pipeline.jobs.simulation import simulate
from hubbeam.pipeline.runner import run

run(simulate, snakemake)
