"""Snakemake shim of every rule: run the job function the rule's step names (``params.job``)
through the runner (:func:`hubbeam.pipeline.runner.run`)."""

from hubbeam.pipeline.runner import run

run(snakemake)
