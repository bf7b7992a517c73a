"""The job of the non-uniform beam checks (rule ``validate_nonuniform`` in ``validate.smk``,
docs/validation.md): the frequencies of a non-uniform beam from the Ritz model against our finite
elements and pyBModes."""

from __future__ import annotations

import logging

from hubbeam.pipeline.runner import Job
from hubbeam.results.io import staged
from hubbeam.validation.nonuniform import nonuniform_tables

LOG = logging.getLogger(__name__)


def validate_nonuniform(job: Job) -> None:
    """The frequencies of a non-uniform beam from the Ritz model against our finite elements
    (``output.ritz_fe``) and, when the rule has that output, against pyBModes (``output.pybmodes``)."""
    outputs = job.output
    tables = nonuniform_tables(job.params["beam"], pybmodes="pybmodes" in outputs)
    for name, table in tables.items():
        with staged(outputs[name]) as (path,):
            table.to_csv(path, index=False)
        LOG.info("%s\n%s", name, table.to_string(index=False))
