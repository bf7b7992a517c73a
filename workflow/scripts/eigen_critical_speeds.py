"""Snakemake shim: critical speeds over tip mass x position (netCDF)."""

import numpy as np

from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import critical_speed_sweep
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
ds = critical_speed_sweep(beam_from_config(p.beam), p.tip_masses, np.linspace(**p.positions), p.n_modes,
                          p.search_max, p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"critical speeds: {dict(ds.sizes)}", file=log)
