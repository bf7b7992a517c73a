"""Snakemake shim: Campbell diagram data, TLAM and FOAM frequencies against hub speed."""

import numpy as np

from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import campbell
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
ds = campbell(beam_from_config(p.beam), p.tip_masses, np.linspace(**p.speeds), p.n_modes, p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"Campbell diagram: {dict(ds.sizes)}", file=log)
