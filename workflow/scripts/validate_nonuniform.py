"""Snakemake shim: frequencies of a non-uniform beam, Ritz vs our finite elements vs pyBModes."""

from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import staged
from hubbeam.validation.nonuniform import nonuniform_tables

outputs = dict(snakemake.output.items())
tables = nonuniform_tables(beam_from_config(snakemake.params.beam), pybmodes="pybmodes" in outputs)
with open(snakemake.log[0], "w") as log:
    for name, table in tables.items():
        with staged(outputs[name]) as (csv,):
            table.to_csv(csv, index=False)
        print(f"{name}\n{table.to_string(index=False)}", file=log)
