"""Snakemake shim: compile the simulation kernel of one family of models into numba's cache.

Runs :func:`hubbeam.pipeline.jobs.simulation.simulation_kernel` through the runner.
"""

from hubbeam.pipeline.jobs.simulation import simulation_kernel
from hubbeam.pipeline.runner import run

run(simulation_kernel, snakemake)
