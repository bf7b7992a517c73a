"""Snakemake shim: eigenvalues of K22 over tip mass x position x speed (Fig. 9)."""

import numpy as np

from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import k22_sweep
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
params = beam_from_config(p.beam)
ds = k22_sweep(params, p.tip_masses, np.linspace(**p.positions), np.linspace(**p.speeds),
               p.n_modes, p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"K22 eigenvalues: {dict(ds.sizes)}", file=log)
