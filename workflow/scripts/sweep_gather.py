"""Snakemake shim: join the chunks of a parameter sweep into its map (rule sweep) and write it."""

import logging

from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.simulation.sweep import gather_chunks

logging.basicConfig(filename=snakemake.log[0], filemode="w", level=logging.INFO, force=True,
                    format="%(asctime)s %(name)s %(levelname)s %(message)s")
params = beam_from_config(snakemake.params.beam)
chunks = [open_result(path) for path in snakemake.input.chunks]
ds = gather_chunks(snakemake.params.sweep, params, chunks)
write_netcdf(ds, snakemake.output[0])
logging.info("sweep %s: %d chunks gathered, %d simulations, %d diverged", ds.attrs["sweep_name"],
             len(chunks), ds.attrs["n_simulations"], ds.attrs["n_diverged"])
