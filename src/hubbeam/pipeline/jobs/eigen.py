"""Jobs of the eigen-analysis at constant hub speed (rules in ``eigen.smk``): K22's eigenvalues
(Fig. 9), the critical speeds (Sections 4.2, 4.4) as a map and as the table the claims read, the
Campbell diagram, the beam as data, Table 2."""

from __future__ import annotations

import logging

import xarray as xr

from hubbeam.model.eigen import campbell, critical_speed_sweep, critical_speed_table, k22_sweep, table2
from hubbeam.model.shapes import beam_dataset
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes

LOG = logging.getLogger(__name__)


def _write(ds: xr.Dataset, path: str) -> None:
    """Write an analysis dataset with the global attributes of a result file."""
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, path)
    LOG.info("%s -> %s", dict(ds.sizes), path)


def eigen_k22(job: Job) -> None:
    """The eigenvalues of K22 over tip mass x position x speed (Fig. 9) -> ``output.nc``."""
    p = job.params
    _write(k22_sweep(p["beam"], p["tip_masses"], p["positions"].values,
                     p["speeds"].values, p["n_modes"], p["n_quad"]), job.output["nc"])


def eigen_critical_speeds(job: Job) -> None:
    """The critical speeds over tip mass x position -> ``output.nc``."""
    p = job.params
    _write(critical_speed_sweep(p["beam"], p["tip_masses"], p["positions"].values,
                                p["n_modes"], p["search_max"], p["n_quad"]), job.output["nc"])


def eigen_critical_speed_table(job: Job) -> None:
    """The critical speed of each tip mass at the beam tip, the table the claims read -> ``output.csv``."""
    p = job.params
    table = critical_speed_table(p["beam"], p["tip_masses"], p["n_modes"], p["search_max"],
                                 p["n_quad"])
    with staged(job.output["csv"]) as (csv,):
        table.to_csv(csv, index=False)
    LOG.info("critical speeds:\n%s", table.to_string(index=False))


def eigen_campbell(job: Job) -> None:
    """The Campbell diagram, TLAM and FOAM frequencies against hub speed -> ``output.nc``."""
    p = job.params
    _write(campbell(p["beam"], p["tip_masses"], p["speeds"].values, p["n_modes"],
                    p["n_quad"]), job.output["nc"])


def eigen_beam(job: Job) -> None:
    """The beam as data: its properties along the span, the cases' tip masses and its first mode
    shapes (:func:`hubbeam.model.shapes.beam_dataset`) -> ``output.nc``."""
    p = job.params
    _write(beam_dataset(p["beam"], dict(p["tips"]), p["speeds"], p["tip_masses"],
                        p["n_shapes"], p["n_modes"], p["n_quad"]), job.output["nc"])


def eigen_table2(job: Job) -> None:
    """Table 2: natural and TLAM/FOAM frequencies (Hz) at ``params.speed`` beside the printed ones
    -> ``output.csv``."""
    p = job.params
    table = table2(p["beam"], p["speed"], p["n_modes"], p["n_quad"])
    with staged(job.output["csv"]) as (csv,):
        table.to_csv(csv, index=False)
    LOG.info("Table 2:\n%s", table.to_string(index=False))
