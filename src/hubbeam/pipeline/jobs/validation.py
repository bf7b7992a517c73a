"""Jobs of the independent validation's runs against the Exudyn reference (rules in
``validate.smk``, docs/validation.md): hubbeam's models on the validation cases, their comparison
with the reference per case, the study of the number of modes, and the reference's convergence.
The reference's own runs are in :mod:`hubbeam.pipeline.jobs.reference`, the non-uniform beam
checks in :mod:`hubbeam.pipeline.jobs.eigen`, the validation's figures in
:mod:`hubbeam.pipeline.jobs.figures`: none of their code is an input of these runs."""

from __future__ import annotations

import logging

import pandas as pd
import xarray as xr

from hubbeam.pipeline.jobs.reference import reference_run
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import open_result, staged, write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation.comparison import comparison_dataset, convergence_table, mode_study, simulate_models
from hubbeam.validation.exudyn_model import ExudynNumerics

LOG = logging.getLogger(__name__)
#: the settings the reference's convergence study varies: (its list in ``validation.convergence``,
#: the Exudyn setting), with the units and meaning recorded in the runs' dataset
CONVERGENCE_SETTINGS = {"elements": "elements", "time_steps": "time_step", "newton_tolerances": "newton_tolerance"}
CONVERGENCE_VARIABLES = (("elements", "1", "number of ANCF cable elements"),
                         ("time_step", "s", "generalised-alpha time step"),
                         ("newton_tolerance", "1", "Newton increment tolerance"),
                         ("cpu_time_s", "s", "wall time of the Exudyn solve"),
                         ("newton_iterations", "1", "total Newton iterations"))


def validate_models(job: Job) -> None:
    """The tip outputs of hubbeam's models ``params.models`` for validation case ``params.name``."""
    p = job.params
    ds = simulate_models(p["case"], p["models"], p["beam"], p["numerics"])
    ds.attrs.pop("case_config")
    ds.attrs = global_attributes(f"hubbeam models {', '.join(p['models'])}, validation case {p['name']}",
                                 case_config=p["case"].to_dict(), extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s", ds[["diverged", "diverged_at_s", "n_steps"]].to_dataframe().to_string())


def validate_case(job: Job) -> None:
    """The reference's and the models' tip deflections of validation case ``params.name``, with
    their differences."""
    ds = comparison_dataset(open_result(job.input["reference"]), open_result(job.input["models"]))
    models = ", ".join(map(str, ds["model"].values))
    ds.attrs = global_attributes(f"tip deflection of {models} against the Exudyn ANCF reference, "
                                 f"validation case {job.params['name']}", extra=ds.attrs)
    write_netcdf(ds, job.output["nc"])
    LOG.info("%s", abs(ds["difference"]).max("time").to_dataframe().to_string())


def validate_modes(job: Job) -> None:
    """The models' tip differences from the reference (``input.references``, one per validation
    case of ``params.cases``, in its order) against the number of assumed modes ``params.modes``."""
    p = job.params
    table = pd.concat([mode_study(case, p["models"], p["modes"], p["beam"], p["numerics"], open_result(path))
                       for case, path in zip(p["cases"].values(), job.input["references"])],
                      ignore_index=True)
    with staged(job.output["csv"]) as (path,):
        table.to_csv(path, index=False)
    LOG.info("%s", table.to_string(index=False))


def validate_convergence(job: Job) -> None:
    """The convergence of the Exudyn reference on case ``params.case``: the production settings
    ``params.exudyn`` and each setting of ``params.convergence`` varied alone -> ``output.table``
    and the runs ``output.runs``."""
    p = job.params
    production = p["exudyn"].to_dict()
    settings = {tuple(sorted(production.items()))}
    for key, name in CONVERGENCE_SETTINGS.items():
        settings |= {tuple(sorted({**production, name: value}.items())) for value in getattr(p["convergence"], key)}
    runs = {}
    for setting in sorted(settings):
        numerics = ExudynNumerics(**dict(setting), output_step=p["output_step"])
        label = f"n{numerics.elements}_h{numerics.time_step:g}_tol{numerics.newton_tolerance:g}"
        runs[label] = reference_run(p["beam"], p["case"], numerics)
    table = convergence_table(runs, production)
    with staged(job.output["table"]) as (path,):
        table.to_csv(path, index=False)
    labels = list(runs)
    stacked = xr.concat([runs[label]["tip_transverse"] for label in labels], dim="run")
    ds = xr.Dataset(
        {"tip_transverse": stacked.assign_attrs(runs[labels[0]]["tip_transverse"].attrs),
         **{name: ("run", [runs[label].attrs[f"exudyn_{name}"] for label in labels],
                   {"units": units, "long_name": long_name})
            for name, units, long_name in CONVERGENCE_VARIABLES}},
        coords={"run": ("run", labels, {"long_name": "run label", "units": "1"})},
    )
    ds.attrs = global_attributes("convergence of the Exudyn ANCF reference", case_config=p["case"].to_dict(),
                                 extra={"production_settings": production, "convergence_case": p["convergence"].case})
    write_netcdf(ds, job.output["runs"])
    LOG.info("%s", table.to_string(index=False))
