"""Snakemake shim: compile the parameter-sweep kernel into numba's cache.

Runs :func:`hubbeam.pipeline.jobs.sweeps.sweep_kernel` through the runner.
"""

from hubbeam.pipeline.jobs.sweeps import sweep_kernel
from hubbeam.pipeline.runner import run

run(sweep_kernel, snakemake)
