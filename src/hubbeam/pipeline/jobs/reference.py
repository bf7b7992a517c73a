"""The job of the Exudyn ANCF reference's runs (rule ``validate_exudyn`` in ``validate.smk``,
docs/validation.md): one prescribed spin-up of a validation case. The costliest job of the
workflow, alone in its module so that its code inputs are the reference's own modules."""

from __future__ import annotations

import json
import logging
from collections.abc import Mapping

import xarray as xr

from hubbeam.model.beam import beam_from_config
from hubbeam.model.parameters import TipMass
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.exudyn_model import ExudynNumerics, spin_up

LOG = logging.getLogger(__name__)


def reference_run(beam: Mapping, case: Mapping, numerics: ExudynNumerics) -> xr.Dataset:
    """The Exudyn spin-up of the validation ``case``."""
    tip = TipMass(**case["tip_mass"]) if "tip_mass" in case else None
    maneuver = case["maneuver"]
    return spin_up(beam_from_config(beam), tip, maneuver["wf"], maneuver["tf"], case["t_end"], numerics)


def validate_exudyn(job: Job) -> None:
    """One prescribed spin-up of the Exudyn ANCF reference, validation case ``params.name``."""
    p = job.params
    ds = reference_run(p["beam"], p["case"], ExudynNumerics(**p["exudyn"], output_step=p["output_step"]))
    ds.attrs = global_attributes(f"Exudyn ANCF reference, validation case {p['name']}", case_config=dict(p["case"]),
                                 extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s", json.dumps({key: ds.attrs[key] for key in ds.attrs if key.startswith("exudyn_")}))
