"""The study report's section on the ``identify`` section: the fit, read from its dataset
(``identification/fit.nc``, :mod:`hubbeam.identification.dataset`) without importing the
identification.

:func:`identification_markdown` gives the free parameters (bounds, start, fitted value, standard
error, 95 % interval, whether the data determine it and, if not, why), the strongly correlated
pairs, each experiment fitted or held out with its weighted residuals and its error (the held-out
ones are the validation), the cases that run the fitted values with a link to the fitted fragment,
and the figures of measured against fitted.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from hubbeam.reporting.document import markdown_table
from hubbeam.reporting.formatting import number

#: correlations whose magnitude reaches this are listed below the parameters' table
LISTED_CORRELATION = 0.9
#: how an experiment's error is measured, by kind (``hubbeam.identification.fit.Validation``)
ERROR_MEASURE = {"modal": "RMS relative error of the frequencies",
                 "frequency_response": "RMS of |ln H_model / H|",
                 "time_series": "1 - fit, fit = 1 - |y - y_model| / |y - mean y|"}
ROLE = {"fitted": "fitted", "held_out": "held out (predicted)"}


def parameter_rows(fit: xr.Dataset) -> list[list]:
    """One row per free parameter (module docstring)."""
    rows = []
    for k, key in enumerate(fit["parameter"].values):
        one = fit.isel(parameter=k)
        identifiable = bool(int(one["identifiable"]))
        interval = (f"[{number(float(one['lower_95']))}, {number(float(one['upper_95']))}]"
                    if np.isfinite(float(one["lower_95"])) else "-")
        rows.append([f"`{key}`", str(one["parameter_units"].values), f"[{number(float(one['lower_bound']))}, "
                     f"{number(float(one['upper_bound']))}]", float(one["start_value"]), float(one["value"]),
                     float(one["standard_error"]), interval,
                     "yes" if identifiable else f"**no**: {one['reason'].values}"])
    return rows


def correlated_pairs(fit: xr.Dataset, limit: float = LISTED_CORRELATION) -> list[tuple[str, str, float]]:
    """The pairs of parameters whose estimates correlate at ``limit`` or more in magnitude."""
    keys = [str(key) for key in fit["parameter"].values]
    matrix = fit["correlation"].values
    return [(keys[i], keys[j], float(matrix[i, j])) for i in range(len(keys)) for j in range(i + 1, len(keys))
            if abs(matrix[i, j]) >= limit]


def identification_markdown(fit: xr.Dataset, figures: Mapping[str, str], applied: Sequence[str],
                            fitted_file: str) -> str:
    """The section (module docstring) of the fit ``fit``; ``figures``: the PNG paths relative to the
    report by experiment name (and ``parameters``), ``applied`` the cases that run the fitted values,
    ``fitted_file`` the fitted fragment relative to the report."""
    experiments = json.loads(fit.attrs["experiments"])
    lines = [f"Case `{fit.attrs['case']}` fitted by weighted least squares to "
             f"{', '.join(e['name'] for e in experiments if e['role'] == 'fitted')} "
             f"({fit.attrs['evaluations']} model evaluations from {fit.sizes['start']} starts, cost "
             f"{number(float(fit.attrs['cost']))}, residual variance s2 = {number(float(fit.attrs['s2']))} with "
             f"{fit.attrs['dof']} degrees of freedom). Intervals are {float(fit.attrs['confidence']):.0%} "
             "intervals from the Jacobian at the fit, scaled by s2. A parameter is not identifiable when its "
             f"estimate lies at a bound (within {number(float(fit.attrs['at_bound_fraction']))} of its range), "
             "correlates with another's at "
             f"{number(float(fit.attrs['correlation_limit']))} or more, or lies along a direction of the "
             f"Jacobian whose singular value is below {number(float(fit.attrs['singular_ratio']))} of the largest: "
             "a result about the experiments, not a failure of the fit.", "",
             markdown_table(["parameter", "units", "bounds", "start", "fitted", "standard error", "95 % interval",
                             "identifiable"], parameter_rows(fit), "llcrrrcl")]
    pairs = correlated_pairs(fit)
    if pairs:
        lines += ["", "Strongly correlated estimates: " + "; ".join(
            f"`{a}` and `{b}` ({number(r, 4)})" for a, b, r in pairs) + "."]
    lines += ["", "Each experiment against the fitted model (the held-out ones were not fitted: their errors "
              "validate the fit). The weighted residual is the residual over its standard uncertainty: about 1 "
              "where the model explains the data to their noise.", "",
              markdown_table(["experiment", "kind", "role", "RMS weighted residual", "error", "error measure"],
                             [[e["name"], e["kind"].replace("_", " "), ROLE[e["role"]], e["rms_weighted_residual"],
                               e["error"], ERROR_MEASURE[e["kind"]]] for e in experiments], "lllrrl")]
    if applied:
        lines += ["", f"The cases {', '.join(f'`{name}`' for name in applied)} run on the fitted values (their runs, "
                  f"plant products, designs and exported controllers): the fragment [{fitted_file}]({fitted_file})."]
    else:
        lines += ["", f"No case runs on the fitted values (`identify.apply_to`); the fitted plant as a fragment "
                  f"a study can merge: [{fitted_file}]({fitted_file})."]
    for name, path in figures.items():
        lines += ["", f"![{name}]({path})"]
    return "\n".join(lines)


__all__ = ["correlated_pairs", "identification_markdown", "parameter_rows"]
