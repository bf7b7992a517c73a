"""Snakemake shim: compile the simulation kernel of one family of models into numba's on-disk
cache (once per source; rule simulation_kernel)."""

import os

from hubbeam.results.io import write_text
from hubbeam.simulation.simulate import compile_kernels

family = snakemake.params.family
seconds = compile_kernels(family)
cache = os.environ.get("NUMBA_CACHE_DIR")
message = f"simulation kernel of the {family} family ready in {seconds:.1f} s (numba cache {cache})"
with open(snakemake.log[0], "w") as log:
    print(message, file=log)
write_text(snakemake.output[0], message + "\n")
