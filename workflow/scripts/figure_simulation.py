"""Snakemake shim: draw one simulation figure (Figs. 3-8, 10, convergence) from its case files."""

from hubbeam.plotting import render_files

p = snakemake.params
written = render_files(p.figure, dict(zip(p.cases, snakemake.input.datasets)), snakemake.output.pdf)
with open(snakemake.log[0], "w") as log:
    print(f"{p.figure}: cases {', '.join(p.cases)} -> {', '.join(map(str, written))}", file=log)
