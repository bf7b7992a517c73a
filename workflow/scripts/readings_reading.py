"""Snakemake shim: one alternative reading -> its claim rows, results/readings/claims/<reading>.csv."""

import logging

from hubbeam.paper.claims import read_claims
from hubbeam.paper.readings import evaluate_reading, reading_rows, write_rows
from hubbeam.results.io import staged

logging.basicConfig(filename=snakemake.log[0], filemode="w", level=logging.INFO, force=True,
                    format="%(asctime)s %(name)s %(levelname)s %(message)s")
name = snakemake.params.runs.name
simulations = dict(zip(snakemake.params.cases, snakemake.input.datasets))
rows, runs = evaluate_reading(snakemake.params.runs, simulations, snakemake.input.table2,
                              snakemake.input.critical_speeds)
default = {row["id"]: row for row in read_claims(snakemake.input.claims)}
with staged(snakemake.output[0]) as (path,):
    write_rows(reading_rows(name, rows, default), path)
logging.info("reading %s: generated runs %s", name, ", ".join(runs) or "none (measure only)")
for row in rows:
    logging.info("%-12s %s: paper %s, computed %.6g", row["verdict"], row["id"], row["paper"], row["computed"])
