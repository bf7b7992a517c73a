"""Snakemake shim: a study figure of simulations, per case (one simulation, e.g.
``hubbeam.plotting.case_figure``) or per comparison (the simulations by case name, e.g.
``hubbeam.plotting.comparison``), drawn by the product's function (``params.function``); the named
inputs other than ``code`` are the simulation files (``params.per_case``: one, passed alone)."""

from pathlib import Path

from hubbeam.plotting import draw
from hubbeam.reporting.products import resolve
from hubbeam.results.io import open_result, staged

p = snakemake.params
files = {name: path for name, path in snakemake.input.items() if name != "code"}
datasets = {name: open_result(path) for name, path in files.items()}
data = next(iter(datasets.values())) if p.per_case else datasets
written = [Path(snakemake.output.pdf), Path(snakemake.output.png)]
with staged(*written) as (pdf, _png):  # save_figure writes the PNG beside the PDF
    draw(resolve(p.function), pdf, p.name, data)
with open(snakemake.log[0], "w") as log:
    print(f"{p.function}({p.name!r}, {files}) -> {', '.join(map(str, written))}", file=log)
