"""Snakemake shim: the robustness maps of the sampled controllers (control.robustness).

Runs :func:`hubbeam.pipeline.jobs.control.control_robustness` through the runner.
"""

from hubbeam.pipeline.jobs.control import control_robustness
from hubbeam.pipeline.runner import run

run(control_robustness, snakemake)
