"""Snakemake shim: rotating-cantilever frequencies of the FOAM linearisation vs published tables."""

import sys

import numpy as np

from hubbeam.plotting import draw
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation import figures, published, rotating_eigen

p = snakemake.params
modes = p.published["modes"]
table = rotating_eigen.published_comparison(modes, p.n_quad)
with staged(snakemake.output.table) as (csv,):
    table.to_csv(csv, index=False)
tip_mass = rotating_eigen.tip_mass_comparison(modes[-2:], p.n_quad)
with staged(snakemake.output.tip_mass) as (csv,):
    tip_mass.to_csv(csv, index=False)

curves = rotating_eigen.frequency_curves(np.linspace(**p.published["gammas"]), 70.0, 0.0,
                                         max(modes), p.n_quad)
curves.attrs = global_attributes(curves.attrs.pop("title"), extra={
    **curves.attrs, "published_sources": "; ".join(published.CITATIONS.values())})
write_netcdf(curves, snakemake.output.curves)
with staged(snakemake.output.pdf, snakemake.output.png) as (pdf, _png):  # PNG beside the PDF
    draw(figures.rotating_frequencies, pdf, curves, table)

# A value that is not reproduced is a result, reported with its verdict in the reproduction
# report (like a claim of the paper that differs), and announced here; it does not stop the run.
disagreeing = [part[~part["agrees"]] for part in (table, tip_mass)]
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
    print(tip_mass.to_string(index=False), file=log)
    if any(len(part) for part in disagreeing):
        message = "published values not reproduced:\n" + "\n".join(
            part.to_string(index=False) for part in disagreeing if len(part))
        print(message, file=log)
        print(f"WARNING: {message}", file=sys.stderr)
