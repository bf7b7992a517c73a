"""Snakemake shim: Markdown and LaTeX renderings of Table 2 (its csv comes from the eigen rule)."""

from hubbeam.tables import table2, to_markdown, write_table

table = table2(snakemake.input.csv, snakemake.params.speed)
write_table(table, snakemake.input.csv, csv=False)
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
