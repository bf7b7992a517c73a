"""Snakemake shim: one dataset of the linear models (``params.product``: the tracked Campbell
diagram, the poles and zeros over speed or the Bode diagrams, ``hubbeam.linear.datasets``)."""

import numpy as np

from hubbeam.linear import datasets
from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
beam = beam_from_config(p.beam)
common = dict(n_modes=p.n_modes, n_quad=p.n_quad, damping=p.damping)
if p.product == "bode":
    omega = np.geomspace(p.frequencies["start"], p.frequencies["stop"], p.frequencies["num"])
    ds = datasets.bode(beam, p.tip_masses, p.bode_speeds, omega, **common)
else:
    ds = getattr(datasets, p.product)(beam, p.tip_masses, np.linspace(**p.speeds), **common)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"{p.product}: {dict(ds.sizes)} -> {snakemake.output[0]}", file=log)
