"""Jobs of the validation's comparisons with independent results that come with a figure (rules in
``validate.smk``, docs/validation.md): the rotating-cantilever frequencies against the published
tables, and the models against the Exudyn reference."""

from __future__ import annotations

import logging

from hubbeam.pipeline.runner import Job
from hubbeam.plotting import draw
from hubbeam.results.io import open_result, staged, write_netcdf
from hubbeam.results.provenance import global_attributes
from hubbeam.validation import figures as validation_figures
from hubbeam.validation import published, rotating_eigen
from hubbeam.validation.comparison import comparison_table

LOG = logging.getLogger(__name__)


def validate_published(job: Job) -> None:
    """Rotating-cantilever frequencies of the FOAM linearisation against the published tables
    (``params.published``: the modes and the speed grid) -> the comparison tables, the frequency
    curves and their figure. A value not reproduced is a result, reported with its verdict, and
    announced as a warning; it does not stop the run."""
    p, out = job.params, job.output
    modes = list(p["published"].modes)
    table = rotating_eigen.published_comparison(modes, p["n_quad"])
    with staged(out["table"]) as (csv,):
        table.to_csv(csv, index=False)
    tip_mass = rotating_eigen.tip_mass_comparison(modes[-2:], p["n_quad"])
    with staged(out["tip_mass"]) as (csv,):
        tip_mass.to_csv(csv, index=False)
    curves = rotating_eigen.frequency_curves(p["published"].gammas.values, 70.0, 0.0, max(modes),
                                             p["n_quad"])
    curves.attrs = global_attributes(curves.attrs.pop("title"), extra={
        **curves.attrs, "published_sources": "; ".join(published.CITATIONS.values())})
    write_netcdf(curves, out["curves"])
    with staged(out["pdf"], out["png"]) as (pdf, _png):
        draw(validation_figures.rotating_frequencies, pdf, curves, table)
    LOG.info("published frequencies:\n%s\n%s", table.to_string(index=False), tip_mass.to_string(index=False))
    disagreeing = [part[~part["agrees"]] for part in (table, tip_mass)]
    if any(len(part) for part in disagreeing):
        LOG.warning("published values not reproduced:\n%s",
                    "\n".join(part.to_string(index=False) for part in disagreeing if len(part)))


def validate_comparison(job: Job) -> None:
    """The table and the figure of the models against the Exudyn reference, from the comparison
    of every validation case (``input.cases`` of ``params.cases``)."""
    datasets = {case: open_result(path) for case, path in zip(job.params["cases"], job.input["cases"])}
    table = comparison_table(datasets)
    with staged(job.output["table"]) as (csv,):
        table.to_csv(csv, index=False)
    with staged(job.output["pdf"], job.output["png"]) as (pdf, _png):
        draw(validation_figures.exudyn_comparison, pdf, datasets)
    LOG.info("comparison with the Exudyn reference:\n%s", table.to_string(index=False))
