"""Snakemake shim: compile the parameter-sweep kernel into numba's on-disk cache."""

import os

from hubbeam.results.io import write_text
from hubbeam.simulation.sweep import compile_kernel

seconds = compile_kernel()
message = f"sweep kernel ready in {seconds:.1f} s (numba cache {os.environ.get('NUMBA_CACHE_DIR')})"
with open(snakemake.log[0], "w") as log:
    print(message, file=log)
write_text(snakemake.output[0], message + "\n")
