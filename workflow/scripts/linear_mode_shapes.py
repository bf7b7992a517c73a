"""Snakemake shim: the first vibration mode shapes along the span at the first and the last speed
of the tracked Campbell diagram (``hubbeam.linear.datasets.mode_shapes``)."""

from hubbeam.linear.datasets import mode_shapes
from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
ds = mode_shapes(open_result(snakemake.input.campbell), beam_from_config(p.beam), p.shapes)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"mode shapes: {dict(ds.sizes)} -> {snakemake.output[0]}", file=log)
