"""The figures of a study's identification (rule ``identification_figures``): each experiment
measured against the fitted model and the parameters with their intervals, drawn from the fit's
dataset (``identification/fit.nc``, written when the plan was made: :mod:`hubbeam.calibration`)
by :mod:`hubbeam.plotting.identification`, each as PDF with its PNG beside it."""

from __future__ import annotations

import logging
from pathlib import Path

from hubbeam.pipeline.runner import Job
from hubbeam.plotting import draw
from hubbeam.plotting.identification import plot_modes, plot_parameters, plot_response, plot_time_series
from hubbeam.results.io import open_result, staged

LOG = logging.getLogger(__name__)
#: the figure of an experiment by its kind (a free decay is the modal test of its decrement)
PLOTS = {"modal": plot_modes, "free_decay": plot_modes, "frequency_response": plot_response,
         "time_series": plot_time_series}
#: the figure of the parameters' name
PARAMETERS = "parameters"


def identification_figures(job: Job) -> None:
    """Every figure of ``params.figures`` (figure name -> the experiment's kind, or ``parameters``)
    from ``input.fit``; the outputs ``files`` are each figure's PDF and PNG, in that order."""
    fit = open_result(job.input["fit"])
    files = [Path(path) for path in job.output["files"]]
    with staged(*files) as written:
        for k, (name, kind) in enumerate(job.params["figures"].items()):
            pdf = written[2 * k]
            if kind == PARAMETERS:
                draw(plot_parameters, pdf, fit)
            else:
                draw(PLOTS[kind], pdf, fit, name)
    LOG.info("%d figures of %s -> %s", len(job.params["figures"]), job.input["fit"], files[0].parent)


__all__ = ["PARAMETERS", "PLOTS", "identification_figures"]
