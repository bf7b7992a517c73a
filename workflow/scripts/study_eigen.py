"""Snakemake shim: Campbell diagram and critical speeds of a study's beam (``hubbeam.eigen``)."""

import numpy as np

from hubbeam.beam import beam_from_config
from hubbeam.eigen import campbell, critical_speed_sweep
from hubbeam.io import write_netcdf
from hubbeam.provenance import global_attributes

p = snakemake.params
params = beam_from_config(p.beam)
results = {
    "campbell": campbell(params, p.tip_masses, np.linspace(**p.speeds), p.n_modes, p.n_quad),
    "critical": critical_speed_sweep(params, p.tip_masses, np.linspace(**p.positions), p.n_modes,
                                     p.search_max, p.n_quad),
}
with open(snakemake.log[0], "w") as log:
    for name, ds in results.items():
        ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
        write_netcdf(ds, snakemake.output[name])
        print(f"{name}: {dict(ds.sizes)}", file=log)
