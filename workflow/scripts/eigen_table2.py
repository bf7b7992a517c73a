"""Snakemake shim: Table 2, natural and TLAM/FOAM frequencies (Hz) beside the printed values."""

from hubbeam.eigen import table2
from hubbeam.parameters import BeamParameters

p = snakemake.params
table = table2(BeamParameters.from_config({"beam": p.beam}), p.speed, p.n_modes, p.n_quad)
table.to_csv(snakemake.output[0], index=False)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
