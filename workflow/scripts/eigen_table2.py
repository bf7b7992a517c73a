"""Snakemake shim: Table 2, natural and TLAM/FOAM frequencies (Hz) beside the printed values."""

from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import table2
from hubbeam.results.io import staged

p = snakemake.params
table = table2(beam_from_config(p.beam), p.speed, p.n_modes, p.n_quad)
with staged(snakemake.output[0]) as (csv,):
    table.to_csv(csv, index=False)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
