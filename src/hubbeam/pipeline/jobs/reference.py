"""The job of the Exudyn ANCF reference's runs (rule ``validate_exudyn`` in ``validate.smk``,
docs/validation.md): one prescribed spin-up of a validation case. The costliest job of the
workflow, alone in its module so that its code inputs are the reference's own modules."""

from __future__ import annotations

import json
import logging

import xarray as xr

from hubbeam.configuration.sections import ValidationCase
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.exudyn_model import ExudynNumerics, spin_up

LOG = logging.getLogger(__name__)


def reference_run(beam, case: ValidationCase, numerics: ExudynNumerics) -> xr.Dataset:
    """The Exudyn spin-up of the validation ``case`` of ``beam``."""
    return spin_up(beam, case.tip_mass, case.maneuver.wf, case.maneuver.tf, case.t_end, numerics)


def validate_exudyn(job: Job) -> None:
    """One prescribed spin-up of the Exudyn ANCF reference, validation case ``params.name``."""
    p = job.params
    ds = reference_run(p["beam"], p["case"], ExudynNumerics(**p["exudyn"].to_dict(), output_step=p["output_step"]))
    ds.attrs = global_attributes(f"Exudyn ANCF reference, validation case {p['name']}",
                                 case_config=p["case"].to_dict(), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s", json.dumps({key: ds.attrs[key] for key in ds.attrs if key.startswith("exudyn_")}))
