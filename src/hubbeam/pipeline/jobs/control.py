"""Jobs of the configuration's ``control`` section (rules in ``control.smk``, docs/quanser-study.md): the
sample-time sweep, the robustness maps and the implementation files of the sampled controllers."""

from __future__ import annotations

import logging

from hubbeam.control.analyses import robustness_analysis, sample_time_analysis
from hubbeam.control.cases import sampled_controller
from hubbeam.control.implementation import write_implementation
from hubbeam.pipeline.runner import Job
from hubbeam.results.io import staged, write_netcdf
from hubbeam.simulation.simulate import case_matrices

LOG = logging.getLogger(__name__)


def control_sample_time(job: Job) -> None:
    """The sample-time sweep of ``params.spec`` (``control.sample_time``) on ``params.settings`` -> ``output.nc``."""
    ds = sample_time_analysis(job.params["settings"], job.params["spec"])
    write_netcdf(ds, job.output["nc"])
    LOG.info("sample-time sweep of %s over %d sample times -> %s", ", ".join(job.params["spec"].cases),
             ds.sizes["sample_time"], job.output["nc"])


def control_robustness(job: Job) -> None:
    """The robustness maps of ``params.spec`` (``control.robustness``) on ``params.settings`` -> ``output.nc``."""
    ds = robustness_analysis(job.params["settings"], job.params["spec"])
    write_netcdf(ds, job.output["nc"])
    LOG.info("robustness maps of %s -> %s", ", ".join(job.params["spec"].cases), job.output["nc"])


def control_export(job: Job) -> None:
    """The implementation files of the sampled controller of case ``params.case`` (``params.settings``)
    -> ``output.mat`` and ``output.json`` (:func:`hubbeam.control.implementation.write_implementation`)."""
    settings, name = job.params["settings"], job.params["case"]
    case = settings.cases[name]
    controller = sampled_controller(case, settings.beam, case_matrices(case, settings.beam, settings.numerics))
    with staged(job.output["mat"], job.output["json"]) as (mat, _json):  # written beside each other
        write_implementation(controller, mat)
    LOG.info("%s: %s -> %s, %s", name, controller.kind, job.output["mat"], job.output["json"])
