"""Snakemake shim: every reading's claim rows -> results/readings/readings.csv and readings.nc."""

from hubbeam.paper.readings import matrix, read_rows, write_rows
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes

rows = [row for path in snakemake.input.readings for row in read_rows(path)]
with staged(snakemake.output.csv) as (csv,):
    write_rows(rows, csv)
ds = matrix(rows, snakemake.params.readings)
ds.attrs = global_attributes("Claims of the paper under alternative readings",
                             extra={"readings": snakemake.params.readings})
write_netcdf(ds, snakemake.output.nc)
with open(snakemake.log[0], "w") as log:
    print(f"{len(rows)} claim values under {len(snakemake.params.readings)} readings", file=log)
