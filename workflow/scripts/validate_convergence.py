"""Snakemake shim: convergence of the Exudyn reference in elements, time step, Newton tolerance."""

import xarray as xr

from hubbeam.model.beam import beam_from_config
from hubbeam.model.parameters import TipMass
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.comparison import convergence_table
from hubbeam.validation.exudyn_model import ExudynNumerics, spin_up

p = snakemake.params
params = beam_from_config(p.beam)
tip = TipMass(**p.case["tip_mass"]) if "tip_mass" in p.case else None
maneuver = p.case["maneuver"]
studies = {"elements": "elements", "time_steps": "time_step",
           "newton_tolerances": "newton_tolerance"}
settings = {tuple(sorted(p.exudyn.items()))}
for key, field in studies.items():
    settings |= {tuple(sorted({**p.exudyn, field: value}.items()))
                 for value in p.convergence[key]}
runs = {}
for setting in sorted(settings):
    numerics = ExudynNumerics(**dict(setting), output_step=p.output_step)
    label = f"n{numerics.elements}_h{numerics.time_step:g}_tol{numerics.newton_tolerance:g}"
    runs[label] = spin_up(params, tip, maneuver["wf"], maneuver["tf"], p.case["t_end"], numerics)

table = convergence_table(runs, p.exudyn)
with staged(snakemake.output.table) as (csv,):
    table.to_csv(csv, index=False)
labels = list(runs)
stacked = xr.concat([runs[label]["tip_transverse"] for label in labels], dim="run")
ds = xr.Dataset(
    {
        "tip_transverse": stacked.assign_attrs(runs[labels[0]]["tip_transverse"].attrs),
        **{name: ("run", [runs[label].attrs[f"exudyn_{name}"] for label in labels],
                  {"units": units, "long_name": long_name})
           for name, units, long_name in (
               ("elements", "1", "number of ANCF cable elements"),
               ("time_step", "s", "generalised-alpha time step"),
               ("newton_tolerance", "1", "Newton increment tolerance"),
               ("cpu_time_s", "s", "wall time of the Exudyn solve"),
               ("newton_iterations", "1", "total Newton iterations"))},
    },
    coords={"run": ("run", labels, {"long_name": "run label", "units": "1"})},
)
ds.attrs = global_attributes("convergence of the Exudyn ANCF reference", case_config=dict(p.case),
                             extra={"production_settings": dict(p.exudyn),
                                    "convergence_case": p.convergence["case"]})
write_netcdf(ds, snakemake.output.runs)
with open(snakemake.log[0], "w") as log:
    print(table.to_string(index=False), file=log)
