"""Snakemake shim: the study's beam as data, its properties and first mode shapes (``hubbeam.model.shapes``)."""

from hubbeam.model.beam import beam_from_config
from hubbeam.model.shapes import beam_dataset
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
ds = beam_dataset(beam_from_config(p.beam), dict(p.tips),
                  p.speeds, p.tip_masses, p.n_shapes, p.n_modes, p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output.beam)
with open(snakemake.log[0], "w") as log:
    print(f"beam: {dict(ds.sizes)} -> {snakemake.output.beam}", file=log)
