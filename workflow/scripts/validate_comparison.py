"""Snakemake shim: comparison table and figure of the models against the Exudyn reference."""

from pathlib import Path

from hubbeam.plotting import draw
from hubbeam.results.io import open_result, staged
from hubbeam.validation.comparison import comparison_table
from hubbeam.validation.figures import exudyn_comparison

datasets = {Path(path).stem.removeprefix("exudyn_"): open_result(path)
            for path in snakemake.input.cases}
table = comparison_table(datasets)
with staged(snakemake.output.table) as (csv,):
    table.to_csv(csv, index=False)
with staged(snakemake.output.pdf, snakemake.output.png) as (pdf, _png):  # PNG beside the PDF
    draw(exudyn_comparison, pdf, datasets)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
