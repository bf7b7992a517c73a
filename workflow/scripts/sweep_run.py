"""Snakemake shim: run one parameter sweep on the job's threads and write its netCDF atomically."""

import logging

from hubbeam.io import write_netcdf
from hubbeam.parameters import BeamParameters
from hubbeam.sweep import run_sweep

logging.basicConfig(filename=snakemake.log[0], filemode="w", level=logging.INFO, force=True,
                    format="%(asctime)s %(name)s %(levelname)s %(message)s")
params = BeamParameters.from_config({"beam": snakemake.params.beam})
ds = run_sweep(snakemake.params.sweep, params, threads=snakemake.threads)
write_netcdf(ds, snakemake.output[0])
