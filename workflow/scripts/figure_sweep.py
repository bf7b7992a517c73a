"""Snakemake shim: draw a parameter-sweep map from its result file (rule figure_sweep)."""

from hubbeam.plotting import draw
from hubbeam.plotting.sweep_maps import plot
from hubbeam.results.io import open_result

written = draw(plot, snakemake.output.pdf, open_result(snakemake.input.sweep))
with open(snakemake.log[0], "w") as log:
    print(f"sweep map {snakemake.input.sweep} -> {', '.join(map(str, written))}", file=log)
