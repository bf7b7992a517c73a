"""Snakemake shim: one prescribed spin-up of the Exudyn ANCF reference."""

import json

from hubbeam.model.beam import beam_from_config
from hubbeam.model.parameters import TipMass
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.exudyn_model import ExudynNumerics, spin_up

p = snakemake.params
params = beam_from_config(p.beam)
tip = TipMass(**p.case["tip_mass"]) if "tip_mass" in p.case else None
numerics = ExudynNumerics(**p.exudyn, output_step=p.output_step)
maneuver = p.case["maneuver"]
ds = spin_up(params, tip, maneuver["wf"], maneuver["tf"], p.case["t_end"], numerics)
title = f"Exudyn ANCF reference, validation case {snakemake.wildcards.vcase}"
ds.attrs = global_attributes(title, case_config=dict(p.case), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(json.dumps({key: ds.attrs[key] for key in ds.attrs if key.startswith("exudyn_")}),
          file=log)
