"""Snakemake shim: compile the simulation kernel into numba's on-disk cache (once per source)."""

import os

from hubbeam.io import write_text
from hubbeam.simulate import compile_kernels

seconds = compile_kernels()
cache = os.environ.get("NUMBA_CACHE_DIR")
message = f"simulation kernel ready in {seconds:.1f} s (numba cache {cache})"
with open(snakemake.log[0], "w") as log:
    print(message, file=log)
write_text(snakemake.output[0], message + "\n")
