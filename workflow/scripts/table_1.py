"""Snakemake shim: Table 1 (physical parameters) from the configuration, csv + md + tex."""

from hubbeam.paper.tables import table1, to_markdown, write_table
from hubbeam.results.io import staged

table = table1(snakemake.params.beam)
out = snakemake.output
with staged(out.csv, out.md, out.tex) as (csv, _md, _tex):
    write_table(table, csv)
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
