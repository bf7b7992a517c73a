"""Snakemake shim: assemble and write the system matrices of one tip-mass configuration."""

from hubbeam.model.beam import beam_from_config
from hubbeam.model.matrices import assemble, to_dataset
from hubbeam.model.parameters import TipMass
from hubbeam.results.io import write_netcdf
from hubbeam.results.provenance import global_attributes

p = snakemake.params
params = beam_from_config(p.beam)
tip = TipMass(**{key: value for key, value in p.configuration.items() if key != "modes"})
sm = assemble(params, tip, p.configuration["modes"], p.n_quad)
ds = to_dataset(sm, params, tip, n_quad_requested=p.n_quad)
ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(f"{ds.attrs['configuration']}: {ds.attrs['n_modes']} modes, "
          f"{ds.attrs['n_quad']} Gauss nodes (requested {p.n_quad})", file=log)
