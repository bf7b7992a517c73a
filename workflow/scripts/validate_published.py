"""Snakemake shim: rotating-cantilever frequencies of the FOAM linearisation vs published tables."""

import numpy as np

from hubbeam.io import write_netcdf
from hubbeam.plotting import draw
from hubbeam.provenance import global_attributes
from hubbeam.validation import figures, published, rotating_eigen

p = snakemake.params
modes = p.published["modes"]
table = rotating_eigen.published_comparison(modes, p.n_quad)
table.to_csv(snakemake.output.table, index=False)
tip_mass = rotating_eigen.tip_mass_comparison(modes[-2:], p.n_quad)
tip_mass.to_csv(snakemake.output.tip_mass, index=False)

curves = rotating_eigen.frequency_curves(np.linspace(**p.published["gammas"]), 70.0, 0.0,
                                         max(modes), p.n_quad)
curves.attrs = global_attributes(curves.attrs.pop("title"), extra={
    **curves.attrs, "published_sources": "; ".join(published.CITATIONS.values())})
write_netcdf(curves, snakemake.output.curves)
draw(figures.rotating_frequencies, snakemake.output.pdf, curves, table)

with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
    print(tip_mass.to_string(index=False), file=log)
disagreeing = table[~table["agrees"]]
if not tip_mass["agrees"].all() or len(disagreeing):
    raise SystemExit(f"published values not reproduced:\n{disagreeing.to_string(index=False)}\n"
                     f"{tip_mass[~tip_mass['agrees']].to_string(index=False)}")
