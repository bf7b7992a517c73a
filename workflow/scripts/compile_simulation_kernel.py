"""Snakemake shim: compile the simulation kernel into numba's on-disk cache (rule simulation_kernel)."""

import os

from hubbeam.simulate import compile_kernels

seconds = compile_kernels()
message = f"simulation kernel ready in {seconds:.1f} s (numba cache {os.environ.get('NUMBA_CACHE_DIR')})"
with open(snakemake.log[0], "w") as log:
    print(message, file=log)
with open(snakemake.output[0], "w") as done:
    print(message, file=done)
