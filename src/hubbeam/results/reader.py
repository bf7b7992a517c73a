"""The one reader of a simulation dataset, beside its writer :func:`hubbeam.simulation.simulate.build_dataset`.

A simulation dataset (``docs/architecture.md``) holds the variables named in
:mod:`hubbeam.results.variables` and records its case in global attributes. Everything that reads one --
the claims, the tables, the reports, the readings, the study summary, the figures -- goes through
the functions here: a variable by name (with its units), the model, mode count, tip mass and
maneuver of the case, selections of runs by those settings, when a run stopped (diverged or left
the range of the models) and the inputs that rerun it (:func:`simulation_inputs`).

Every function takes the case name with its dataset, so that a missing variable or attribute is
reported as :class:`DatasetError` naming both. Importing this module is cheap (no numba kernel is
compiled, no plotting library is loaded).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.model.beam import beam_from_attributes
from hubbeam.model.maneuvers import maneuver_from_dict
from hubbeam.results.variables import CUMULATIVE_VARIABLES, HIGH_ORDER_VARIABLES, JOINT_VARIABLES, VARIABLES

#: every variable a simulation dataset may hold -> its UDUNITS units (the tables of
#: :mod:`hubbeam.results.variables`; the high-order ones only in CFOAM runs, the joint's only with a
#: compliant root)
UNITS = {name: entry[-2] for table in (VARIABLES, CUMULATIVE_VARIABLES, HIGH_ORDER_VARIABLES, JOINT_VARIABLES)
         for name, entry in table.items()}

#: the ``numerics`` settings a dataset records as attributes, with their types: what
#: :func:`simulation_inputs` hands back to :func:`hubbeam.simulation.simulate.simulate`
NUMERICS_ATTRIBUTES = {"rtol": float, "atol": float, "output_step": float, "max_steps": int,
                       "step_warning": int, "divergence_limit": float,
                       "small_deflection_limit": float, "quadrature_points": int}


class DatasetError(ValueError):
    """A dataset lacks what its reader needs (names the case and the variable or attribute)."""


# --- variables and attributes ---------------------------------------------------------------------

def attr(case: str, ds: xr.Dataset, key: str):
    """Global attribute ``key`` of ``case``'s dataset, or a DatasetError naming both."""
    try:
        return ds.attrs[key]
    except KeyError:
        raise DatasetError(f"dataset of case {case!r} has no attribute {key!r}") from None


def variable(case: str, ds: xr.Dataset, name: str) -> xr.DataArray:
    """Variable ``name`` of ``case``'s dataset (its ``units`` attribute kept), or a DatasetError
    naming both and the variables the dataset has."""
    if name not in ds.data_vars:
        raise DatasetError(
            f"dataset of case {case!r} has no variable {name!r} (has: {', '.join(sorted(ds.data_vars))})")
    return ds[name]


def units(case: str, ds: xr.Dataset, name: str) -> str:
    """The UDUNITS units of variable ``name`` as the dataset records them."""
    return str(variable(case, ds, name).attrs.get("units", UNITS.get(name, "")))


def times(ds: xr.Dataset) -> np.ndarray:
    """The output times (s) of a dataset."""
    return ds["time"].values


def model(case: str, ds: xr.Dataset) -> str:
    return str(attr(case, ds, "model"))


def n_modes(case: str, ds: xr.Dataset) -> int:
    return int(attr(case, ds, "n_modes"))


def tip_mass(case: str, ds: xr.Dataset) -> float:
    return float(attr(case, ds, "tip_mass_kg"))


def tip_position(case: str, ds: xr.Dataset) -> float:
    return float(attr(case, ds, "tip_position_m"))


def _json(case: str, ds: xr.Dataset, key: str) -> dict:
    """The JSON attribute ``key`` as a dict."""
    raw = attr(case, ds, key)
    try:
        return json.loads(raw) if isinstance(raw, str) else dict(raw)
    except (TypeError, ValueError) as err:
        raise DatasetError(f"case {case!r}: attribute {key!r} is not JSON: {raw!r}") from err


def maneuver(case: str, ds: xr.Dataset) -> dict:
    """The ``maneuver`` attribute (JSON) as a dict, e.g. ``{"kind": "prescribed", "wf": 3.0, ...}``."""
    return _json(case, ds, "maneuver")


def case_config(case: str, ds: xr.Dataset) -> dict:
    """The case's settings as the run resolved them (the ``case_config`` attribute, JSON)."""
    return _json(case, ds, "case_config")


def shaper(case: str, ds: xr.Dataset) -> dict | None:
    """The command shaper of a shaped run (the ``shaper`` attribute, JSON: ``name``, ``times``,
    ``amplitudes``, ``modes`` as ``[omega, zeta]`` pairs; ``hubbeam.model.shapers.Shaper.to_dict``),
    None for an unshaped run (which has no such attribute)."""
    return _json(case, ds, "shaper") if "shaper" in ds.attrs else None


def shaper_duration(case: str, ds: xr.Dataset) -> float:
    """How much later the run's shaped command ends than the maneuver (s): its shaper's last
    impulse time, 0 for an unshaped run."""
    found = shaper(case, ds)
    return 0.0 if found is None else float(found["times"][-1])


def maneuver_value(case: str, ds: xr.Dataset, key: str) -> float:
    """One number of the maneuver (``wf``, ``tf``, ``tau_max``), with a clear error if absent."""
    found = maneuver(case, ds)
    if found.get(key) is None:
        raise DatasetError(f"case {case!r}: maneuver has no {key!r} ({found})")
    return float(found[key])


def maneuver_end(found: Mapping) -> float:
    """When the hub input of the maneuver ``found`` (a dataset's ``maneuver`` attribute) stops
    changing, s (:attr:`hubbeam.model.maneuvers.Maneuver.end`)."""
    try:
        return float(maneuver_from_dict(found).end)
    except (KeyError, TypeError) as err:
        raise DatasetError(f"maneuver {dict(found)} is not a maneuver hubbeam knows ({err!r})") from err


# --- how the run ended ------------------------------------------------------------------------------

def diverged_at(case: str, ds: xr.Dataset) -> float | None:
    """Time (s) at which the run diverged, or None when it did not."""
    if int(attr(case, ds, "diverged")) != 1:
        return None
    t = float(ds.attrs.get("diverged_at_s", math.nan))
    if math.isnan(t):  # flag set but no time recorded: last finite sample of the run
        finite = np.isfinite(variable(case, ds, "tip_transverse").values)
        t = float(times(ds)[finite][-1]) if finite.any() else float(times(ds)[0])
    return t


def left_range_at(case: str, ds: xr.Dataset) -> float | None:
    """Time (s) at which the run was stopped outside the range of the models with a bounded
    response (:mod:`hubbeam.model.validity`), or None when it was not."""
    return float(attr(case, ds, "stopped_at_s")) if int(attr(case, ds, "left_range")) == 1 else None


def large_deflection_ratio(case: str, ds: xr.Dataset) -> float | None:
    """``max |v(L)| / L`` of a completed run beyond the small-deflection limit of the models
    (``validity = large_deflection``), None otherwise."""
    if attr(case, ds, "validity") != "large_deflection":
        return None
    return float(attr(case, ds, "max_deflection_ratio"))


def convergence_result(attrs: Mapping) -> str:
    """``not checked``, ``converged`` or ``NOT converged`` from a dataset's attributes (the
    optional convergence check, ``numerics.convergence_check``)."""
    if "convergence_check" not in attrs:
        return "not checked"
    return "NOT converged" if "not converged" in str(attrs.get("warnings", "")) else "converged"


# --- selections -------------------------------------------------------------------------------------

#: the settings :func:`select` and :func:`distinct` compare, besides the numbers of the maneuver
_SETTINGS = {"model": model, "n_modes": n_modes, "tip_mass": tip_mass}


def setting(case: str, ds: xr.Dataset, key: str):
    """``model``, ``n_modes``, ``tip_mass``, or a value of the maneuver (``kind``, ``wf``, ...;
    None when the maneuver has no such key)."""
    return _SETTINGS[key](case, ds) if key in _SETTINGS else maneuver(case, ds).get(key)


def select(datasets: Mapping[str, xr.Dataset], **criteria) -> dict[str, xr.Dataset]:
    """The datasets whose settings (:func:`setting`) equal ``criteria``, numbers to 1e-9.

    Keys: ``model``, ``kind``, ``wf``, ``tau_max``, ``tf``, ``tip_mass``, ``n_modes``.
    """
    def matches(case, ds):
        for key, wanted in criteria.items():
            got = setting(case, ds, key)
            if isinstance(wanted, float) or isinstance(got, float):
                if got is None or not math.isclose(float(got), float(wanted), rel_tol=1e-9, abs_tol=1e-12):
                    return False
            elif got != wanted:
                return False
        return True

    return {case: ds for case, ds in datasets.items() if matches(case, ds)}


def distinct(datasets: Mapping[str, xr.Dataset], key: str) -> list[float]:
    """Sorted distinct values of a maneuver number (``wf``, ``tau_max``) or ``tip_mass``."""
    if key == "tip_mass":
        return sorted({tip_mass(c, ds) for c, ds in datasets.items()})
    return sorted({maneuver_value(c, ds, key) for c, ds in datasets.items()})


# --- rerunning a case -------------------------------------------------------------------------------

def simulation_inputs(attrs: Mapping) -> dict:
    """The arguments of :func:`hubbeam.simulation.simulate.simulate` that reproduce a simulation dataset,
    from its attributes.

    ``simulate(**simulation_inputs(ds.attrs))`` reruns the case of ``ds`` (``case_config``) with
    the beam parameters, integrator settings, Gauss nodes and convergence check recorded in it,
    assembling the matrices itself. Raises :class:`DatasetError` naming a missing attribute.
    """
    def get(key):
        if key not in attrs:
            raise DatasetError(f"dataset attribute {key!r} is missing; allowed: the attributes "
                               "of a dataset written by hubbeam.simulation.simulate.simulate")
        return attrs[key]

    settings = attrs.get("convergence_check")
    return {
        "case": json.loads(get("case_config")),
        "params": beam_from_attributes(attrs),
        "numerics": {key: kind(get(key)) for key, kind in NUMERICS_ATTRIBUTES.items()},
        "convergence_check": json.loads(settings) if settings else None,
    }
