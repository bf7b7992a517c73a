"""Snakemake shim: Markdown and LaTeX renderings of Table 2 (its csv comes from the eigen rule)."""

from hubbeam.paper.tables import table2, to_markdown, write_table
from hubbeam.results.io import staged

table = table2(snakemake.input.csv, snakemake.params.speed)
with staged(snakemake.output.md, snakemake.output.tex) as (md, _tex):
    write_table(table, md.with_suffix(".csv"), csv=False)  # .md and .tex beside that name
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
