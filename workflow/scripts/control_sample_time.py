"""Snakemake shim: the sample-time sweep of the sampled controllers (control.sample_time).

Runs :func:`hubbeam.pipeline.jobs.control.control_sample_time` through the runner.
"""

from hubbeam.pipeline.jobs.control import control_sample_time
from hubbeam.pipeline.runner import run

run(control_sample_time, snakemake)
