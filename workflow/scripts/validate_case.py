"""Snakemake shim: Exudyn reference and model tip deflections of one case, with differences."""

from hubbeam.results.io import open_result, write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.comparison import comparison_dataset

ds = comparison_dataset(open_result(snakemake.input.reference), open_result(snakemake.input.models))
models = ", ".join(map(str, ds["model"].values))
ds.attrs = global_attributes(f"tip deflection of {models} against the Exudyn ANCF reference, "
                             f"validation case {snakemake.wildcards.vcase}", extra=ds.attrs)
write_netcdf(ds, snakemake.output[0])
with open(snakemake.log[0], "w") as log:
    print(abs(ds["difference"]).max("time").to_dataframe().to_string(), file=log)
