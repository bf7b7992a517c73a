"""Snakemake shim: a study figure of simulations, per case (``hubbeam.plotting.case_figure``, one
simulation) or per comparison (``hubbeam.plotting.comparison``, the simulations by case name);
the named inputs other than ``code`` are the simulation files."""

import importlib
from pathlib import Path

from hubbeam.io import open_result, staged
from hubbeam.plotting import draw

p = snakemake.params
files = {name: path for name, path in snakemake.input.items() if name != "code"}
datasets = {name: open_result(path) for name, path in files.items()}
plot = importlib.import_module(f"hubbeam.plotting.{p.module}").plot
data = next(iter(datasets.values())) if p.module == "case_figure" else datasets
written = [Path(snakemake.output.pdf), Path(snakemake.output.png)]
with staged(*written) as (pdf, _png):  # save_figure writes the PNG beside the PDF
    draw(plot, pdf, p.name, data)
with open(snakemake.log[0], "w") as log:
    print(f"{p.module}.plot({p.name!r}, {files}) -> {', '.join(map(str, written))}", file=log)
