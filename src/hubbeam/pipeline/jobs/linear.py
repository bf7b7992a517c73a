"""Jobs of the linear models about a steady spin (docs/linear-models.md): the exported state-space
models and the datasets the linear-model figures read, over a set of plants (the paper's grid of
tip masses, or one plant of a study: ``hubbeam.linear.axes``)."""

from __future__ import annotations

import logging
from typing import NamedTuple

from hubbeam.linear import datasets
from hubbeam.linear.export import to_dataset, write_dataset, write_mat
from hubbeam.linear.plant_dataset import plant_dataset
from hubbeam.linear.plant_models import reaches
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.results.provenance import global_attributes

LOG = logging.getLogger(__name__)


class LinearExport(NamedTuple):
    """One exported set of linear models: of ``model`` with the hub ``hub`` (free or prescribed)
    of the plant ``plant`` (its index on the job's plants), over the speed grid, as a netCDF and a
    MATLAB file."""

    plant: int
    model: str
    hub: str
    netcdf: str
    matlab: str


def linear_models(job: Job) -> None:
    """The linear models of every export of ``params.exports`` (:class:`LinearExport`), each of its
    plant of ``params.plants``, over the speed grid ``params.speeds``."""
    p = job.params
    speeds = p["speeds"].values
    for export in p["exports"]:
        plant = p["plants"].plants[export.plant]
        # a driven hub's models where the drive holds the steady spin
        within = [speed for speed in speeds if export.hub == "prescribed" or reaches(plant, "driven", speed)
                  or plant.drive is None] or speeds[:1]
        ds = to_dataset(plant, export.model, within, export.hub)
        write_dataset(ds, export.netcdf)
        write_mat(ds, export.matlab)
        LOG.info("%s, %s hub, %s: %d speeds -> %s, %s", export.model, export.hub, plant.describe(), speeds.size,
                 export.netcdf, export.matlab)


def linear_dataset(job: Job) -> None:
    """One dataset of the linear models of ``params.plants``, ``params.product``: the tracked
    Campbell diagram (``campbell``), the poles and zeros over speed (``poles_zeros``) or the Bode
    diagrams (``bode``, at ``params.bode_speeds`` over ``params.frequencies``) -> ``output.nc``."""
    p = job.params
    if p["product"] == "bode":
        ds = datasets.bode(p["plants"], p["bode_speeds"], p["frequencies"].values)
    else:
        ds = getattr(datasets, p["product"])(p["plants"], p["speeds"].values)
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s: %s -> %s", p["product"], dict(ds.sizes), job.output["nc"])


def linear_mode_shapes(job: Job) -> None:
    """The first ``params.shapes`` vibration mode shapes along the span at the first and the last
    speed of the tracked Campbell diagram (``input.campbell``) of ``params.plants`` -> ``output.nc``."""
    ds = datasets.mode_shapes(open_result(job.input["campbell"]), job.params["plants"], job.params["shapes"])
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("mode shapes: %s -> %s", dict(ds.sizes), job.output["nc"])


def plant_summary(job: Job) -> None:
    """What the plant ``params.plant`` of a study is (:func:`hubbeam.linear.plant_dataset.plant_dataset`):
    its frequencies and their convergence, its free hub's, its critical speeds, the cases that run
    it (``params.cases``) -> ``output.nc``."""
    p = job.params
    ds = plant_dataset(p["plant"], p["cases"], p["search_max"])
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("plant %s: held-hub frequencies %s Hz -> %s", p["plant"].name, ds["held_frequency"].values[:4],
             job.output["nc"])
