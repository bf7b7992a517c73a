"""Snakemake shim: Table 1 (physical parameters) from the configuration, csv + md + tex."""

from hubbeam.tables import table1, to_markdown, write_table

table = table1(snakemake.params.beam, snakemake.params.tip_masses)
write_table(table, snakemake.output.csv)
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
