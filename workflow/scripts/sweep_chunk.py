"""Snakemake shim: simulate one chunk of a parameter sweep on the job's threads (rule sweep_chunk)."""

import logging

from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import write_netcdf
from hubbeam.simulation.sweep import run_chunk

logging.basicConfig(filename=snakemake.log[0], filemode="w", level=logging.INFO, force=True,
                    format="%(asctime)s %(name)s %(levelname)s %(message)s")
params = beam_from_config(snakemake.params.beam)
write_netcdf(run_chunk(snakemake.params.sweep, params, int(snakemake.wildcards.chunk),
                       threads=snakemake.threads), snakemake.output[0])
