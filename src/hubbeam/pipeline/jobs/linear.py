"""Jobs of the linear models about a steady spin (rules in ``linear.smk``, docs/linear-models.md):
the exported state-space models, the datasets the linear-model figures read."""

from __future__ import annotations

import logging
from typing import NamedTuple

from hubbeam.linear import datasets
from hubbeam.linear.export import to_dataset, write_dataset, write_mat
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import TipMass
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.results.provenance import global_attributes

LOG = logging.getLogger(__name__)


class LinearExport(NamedTuple):
    """One exported set of linear models: of ``model`` with the hub ``hub`` (free or prescribed)
    at the tip mass ``linear.tip_masses[tip_mass]``, over the speed grid, as a netCDF and a MATLAB file."""

    tip_mass: int
    model: str
    hub: str
    netcdf: str
    matlab: str


def linear_models(job: Job) -> None:
    """The linear models of every export of ``params.exports`` (:class:`LinearExport`), each at its
    tip mass, over the speed grid, with the configured damping."""
    p = job.params
    beam, damping, speeds = p["beam"], p["damping"], p["speeds"].values
    for k, mass in enumerate(p["tip_masses"]):
        tip = TipMass(mass=float(mass), position=float(beam.L)) if mass > 0 else None
        sm = assemble(beam, tip, p["n_modes"], p["n_quad"])
        C = None if damping is None else damping_matrices(damping, sm)
        for export in (export for export in p["exports"] if export.tip_mass == k):
            ds = to_dataset(beam, sm, export.model, speeds, export.hub, tip, C)
            write_dataset(ds, export.netcdf)
            write_mat(ds, export.matlab)
            LOG.info("%s, %s hub, tip mass %s kg: %d speeds -> %s, %s", export.model, export.hub, mass,
                     speeds.size, export.netcdf, export.matlab)


def linear_dataset(job: Job) -> None:
    """One dataset of the linear models, ``params.product``: the tracked Campbell diagram
    (``campbell``), the poles and zeros over speed (``poles_zeros``) or the Bode diagrams (``bode``,
    at ``params.bode_speeds`` over ``params.frequencies``) -> ``output.nc``."""
    p = job.params
    beam = p["beam"]
    common = dict(n_modes=p["n_modes"], n_quad=p["n_quad"], damping=p["damping"])
    if p["product"] == "bode":
        ds = datasets.bode(beam, p["tip_masses"], p["bode_speeds"], p["frequencies"].values, **common)
    else:
        ds = getattr(datasets, p["product"])(beam, p["tip_masses"], p["speeds"].values, **common)
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s: %s -> %s", p["product"], dict(ds.sizes), job.output["nc"])


def linear_mode_shapes(job: Job) -> None:
    """The first ``params.shapes`` vibration mode shapes along the span at the first and the last
    speed of the tracked Campbell diagram (``input.campbell``) -> ``output.nc``."""
    ds = datasets.mode_shapes(open_result(job.input["campbell"]), job.params["beam"], job.params["shapes"])
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("mode shapes: %s -> %s", dict(ds.sizes), job.output["nc"])
