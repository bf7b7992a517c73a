"""Snakemake shim: evaluate every claim of the paper against the results -> claims.csv."""

from collections import Counter

from hubbeam.paper.claims import Results, evaluate, write_claims
from hubbeam.results.io import staged

results = Results(dict(zip(snakemake.params.cases, snakemake.input.datasets)),
                  table2_csv=snakemake.input.table2,
                  critical_speeds_csv=snakemake.input.critical_speeds)
rows = evaluate(results)
with staged(snakemake.output[0]) as (claims,):
    write_claims(rows, claims)
with open(snakemake.log[0], "w") as log:
    print(f"{len(rows)} claims: {dict(Counter(row['verdict'] for row in rows))}", file=log)
    for row in rows:
        print(f"{row['verdict']:12s} {row['id']}: paper {row['paper']}, computed {row['computed']:.6g}",
              file=log)
