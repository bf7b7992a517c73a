"""Snakemake shim: draw an eigen-analysis figure (Fig. 9, Campbell, critical-speed map).

The named inputs other than ``style`` and ``code`` are opened as datasets and passed to the
product's function (``params.function``) as keyword arguments of the same names, with the
product's ``options`` (e.g. the tip mass a linear-model figure shows).
"""

from pathlib import Path

from hubbeam.plotting import draw
from hubbeam.reporting.products import resolve
from hubbeam.results.io import open_result, staged

files = {name: path for name, path in snakemake.input.items() if name not in ("style", "code")}
datasets = {name: open_result(path) for name, path in files.items()}
written = [Path(snakemake.output.pdf), Path(snakemake.output.pdf).with_suffix(".png")]
with staged(*written) as (pdf, _png):  # save_figure writes the PNG beside the PDF
    draw(resolve(snakemake.params.function), pdf, **datasets, **snakemake.params.options)
with open(snakemake.log[0], "w") as log:
    print(f"{snakemake.params.function}({files}) -> {', '.join(map(str, written))}", file=log)
