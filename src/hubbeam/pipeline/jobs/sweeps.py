"""Jobs of the parameter sweeps (rules in ``sweeps.smk``): the compiled sweep kernel, one chunk of a
map, the map gathered from its chunks."""

from __future__ import annotations

import logging
import os

from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, write_netcdf, write_text
from hubbeam.simulation.sweep import compile_kernel, gather_chunks, run_chunk

LOG = logging.getLogger(__name__)


def sweep_kernel(job: Job) -> None:
    """Compile the sweep kernel into numba's on-disk cache and write the marker ``output.done``."""
    seconds = compile_kernel()
    message = f"sweep kernel ready in {seconds:.1f} s (numba cache {os.environ.get('NUMBA_CACHE_DIR')})"
    LOG.info(message)
    write_text(job.output["done"], message + "\n")


def sweep_chunk(job: Job) -> None:
    """Chunk ``params.chunk`` of the sweep ``params.sweep`` on ``params.threads`` threads -> ``output.nc``."""
    p = job.params
    write_netcdf(run_chunk(p["sweep"], p["beam"], int(p["chunk"]), threads=p["threads"]),
                 job.output["nc"])


def sweep(job: Job) -> None:
    """The map of the sweep ``params.sweep`` from its chunks (``input.chunks``) -> ``output.nc``."""
    chunks = [open_result(path) for path in job.input["chunks"]]
    ds = gather_chunks(job.params["sweep"], job.params["beam"], chunks)
    write_netcdf(ds, job.output["nc"])
    LOG.info("sweep %s: %d chunks gathered, %d simulations, %d diverged -> %s", ds.attrs["sweep_name"],
             len(chunks), ds.attrs["n_simulations"], ds.attrs["n_diverged"], job.output["nc"])
