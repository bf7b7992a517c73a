"""Snakemake shim: critical speeds with each tip mass at the beam tip (csv), which the claims read."""

from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import critical_speed_table
from hubbeam.results.io import staged

p = snakemake.params
table = critical_speed_table(beam_from_config(p.beam), p.tip_masses, p.n_modes, p.search_max, p.n_quad)
with staged(snakemake.output[0]) as (csv,):
    table.to_csv(csv, index=False)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
