"""Snakemake shim: Table 3 (largest |Q_theta| per torque amplitude, FOAM), csv + md + tex."""

from hubbeam.paper.tables import table3, to_markdown, write_table
from hubbeam.results.io import open_result, staged

files = zip(snakemake.params.cases, snakemake.input.datasets)
table = table3({case: open_result(path) for case, path in files})
out = snakemake.output
with staged(out.csv, out.md, out.tex) as (csv, _md, _tex):
    write_table(table, csv)
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
