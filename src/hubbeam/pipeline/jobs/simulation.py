"""Jobs of the simulations (rules in ``simulate.smk`` and ``matrices.smk``): the compiled kernel of a
family of models, the system matrices of a tip-mass configuration, the run of one case."""

from __future__ import annotations

import logging
import os

from hubbeam.control.cases import simulate_case
from hubbeam.model.matrices import assemble, from_dataset, to_dataset
from hubbeam.model.parameters import TipMass
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, write_netcdf, write_text
from hubbeam.results.provenance import global_attributes
from hubbeam.simulation.simulate import compile_kernels

LOG = logging.getLogger(__name__)


def simulation_kernel(job: Job) -> None:
    """Compile the simulation kernel of the family ``params.family`` (its sampled-controller kernel
    with ``params.sampled``) into numba's on-disk cache (once per source) and write the marker
    ``output.done``."""
    family, sampled = job.params["family"], job.params["sampled"]
    seconds = compile_kernels(family, sampled)
    kind = "sampled-controller kernel" if sampled else "simulation kernel"
    message = (f"{kind} of the {family} family ready in {seconds:.1f} s "
               f"(numba cache {os.environ.get('NUMBA_CACHE_DIR')})")
    LOG.info(message)
    write_text(job.output["done"], message + "\n")


def matrices(job: Job) -> None:
    """The system matrices (Eqs. 13-20, Appendix) of one tip-mass configuration,
    ``params.configuration`` (its tip mass or body, transverse functions and mode count), -> ``output.nc``."""
    p = job.params
    beam = p["beam"]
    configuration = dict(p["configuration"])
    modes, functions = configuration.pop("modes"), configuration.pop("functions")
    tip = TipMass(**configuration)
    ds = to_dataset(assemble(beam, tip, modes, p["n_quad"], functions), beam, tip, n_quad_requested=p["n_quad"],
                    functions=functions)
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s: %d modes, %d Gauss nodes (requested %d) -> %s", ds.attrs["configuration"],
             ds.attrs["n_modes"], ds.attrs["n_quad"], p["n_quad"], job.output["nc"])


def simulate(job: Job) -> None:
    """The run of the case ``params.case`` on the leading blocks of the matrices of its tip-mass
    configuration (``input.matrices``, possibly of more modes) -> ``output.nc``."""
    p = job.params
    n_modes = p["case"].modes
    matrices = from_dataset(open_result(job.input["matrices"]), n_modes)
    ds = simulate_case(p["case"], p["beam"], p["numerics"], matrices, convergence_check=p["convergence_check"])
    write_netcdf(ds, job.output["nc"])
    LOG.info("case %s (%s, %d modes): %s -> %s", p["case"].label, p["case"].model, n_modes, ds.attrs["validity"],
             job.output["nc"])
