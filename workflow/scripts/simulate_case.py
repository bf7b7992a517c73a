"""Snakemake shim: simulate one case and write `results/simulations/<case>.nc` atomically."""

import logging

from hubbeam.control.cases import simulate_case
from hubbeam.model.matrices import from_dataset
from hubbeam.results.io import open_result, write_netcdf

logging.basicConfig(filename=snakemake.log[0], filemode="w", level=logging.INFO, force=True,
                    format="%(asctime)s %(name)s %(levelname)s %(message)s")
p = snakemake.params
n_modes = p.case.modes
stored = open_result(snakemake.input.matrices)
matrices = from_dataset(stored.isel(mode=slice(0, n_modes), mode_j=slice(0, n_modes)))
ds = simulate_case(p.case, p.beam, p.numerics, matrices, convergence_check=p.convergence_check)
write_netcdf(ds, snakemake.output[0])
