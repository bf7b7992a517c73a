"""Snakemake shim: tip outputs of the hubbeam models for one validation case."""

from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.comparison import simulate_models

p = snakemake.params
name = snakemake.wildcards.vcase
ds = simulate_models(name, p.case, p.models, beam_from_config(p.beam),
                     p.numerics)
ds.attrs.pop("case_config")
ds.attrs = global_attributes(f"hubbeam models {', '.join(p.models)}, validation case {name}",
                             case_config=dict(p.case), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(ds[["diverged", "diverged_at_s", "n_steps"]].to_dataframe().to_string(), file=log)
