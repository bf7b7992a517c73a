"""Snakemake shim: Table 3 (largest |Q_theta| per torque amplitude, FOAM), csv + md + tex."""

from hubbeam.io import open_result
from hubbeam.tables import table3, to_markdown, write_table

files = zip(snakemake.params.cases, snakemake.input.datasets)
table = table3({case: open_result(path) for case, path in files})
write_table(table, snakemake.output.csv)
with open(snakemake.log[0], "w") as log:
    print(to_markdown(table), file=log)
