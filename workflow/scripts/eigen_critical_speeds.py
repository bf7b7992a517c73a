"""Snakemake shim: critical speeds over tip mass x position (netCDF) and at the beam tip (csv)."""

import numpy as np

from hubbeam.beam import beam_from_config
from hubbeam.eigen import critical_speed_sweep, critical_speed_table
from hubbeam.io import staged, write_netcdf
from hubbeam.provenance import global_attributes

p = snakemake.params
params = beam_from_config(p.beam)
ds = critical_speed_sweep(params, p.tip_masses, np.linspace(**p.positions), p.n_modes,
                          p.search_max, p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output.grid)
table = critical_speed_table(params, p.tip_masses, p.n_modes, p.search_max, p.n_quad)
with staged(snakemake.output.table) as (csv,):
    table.to_csv(csv, index=False)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
