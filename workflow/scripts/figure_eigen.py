"""Snakemake shim: draw an eigen-analysis figure (Fig. 9, Campbell, critical-speed map).

The named inputs other than ``style`` and ``code`` are opened as datasets and passed to
``hubbeam.plotting.<params.module>.plot`` as keyword arguments of the same names.
"""

import importlib

from hubbeam.io import open_result
from hubbeam.plotting import draw

files = {name: path for name, path in snakemake.input.items() if name not in ("style", "code")}
plot = importlib.import_module(f"hubbeam.plotting.{snakemake.params.module}").plot
written = draw(plot, snakemake.output.pdf, **{name: open_result(path) for name, path in files.items()})
with open(snakemake.log[0], "w") as log:
    print(f"{snakemake.params.module}.plot({files}) -> {', '.join(map(str, written))}", file=log)
