"""Snakemake shim: model-reference tip differences against the number of assumed modes."""

from pathlib import Path

import pandas as pd

from hubbeam.model.beam import beam_from_config
from hubbeam.results.io import open_result, staged
from hubbeam.validation.comparison import mode_study

p = snakemake.params
params = beam_from_config(p.beam)
tables = []
for path in snakemake.input.references:
    name = Path(path).stem.removeprefix("exudyn_")
    tables.append(mode_study(name, p.cases[name], p.models, p.modes, params, p.numerics,
                             open_result(path)))
table = pd.concat(tables, ignore_index=True)
with staged(snakemake.output[0]) as (csv,):
    table.to_csv(csv, index=False)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
