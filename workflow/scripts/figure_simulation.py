"""Snakemake shim: draw one simulation figure from its case files (the product's function)."""

from pathlib import Path

from hubbeam.plotting import render_files
from hubbeam.reporting.products import resolve
from hubbeam.results.io import staged

p = snakemake.params
written = [Path(snakemake.output.pdf), Path(snakemake.output.pdf).with_suffix(".png")]
with staged(*written) as (pdf, _png):  # save_figure writes the PNG beside the PDF
    render_files(resolve(p.function), dict(zip(p.cases, snakemake.input.datasets)), pdf)
with open(snakemake.log[0], "w") as log:
    print(f"{p.function}: cases {', '.join(p.cases)} -> {', '.join(map(str, written))}", file=log)
