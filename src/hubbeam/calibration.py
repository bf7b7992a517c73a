"""A configuration with its ``identify`` section fitted: the fit run once, before any job, and
the fitted plant put into the cases of ``identify.apply_to``.

The cases that run on a fitted plant are planned from its values (their runs, their plant
products, the designs on them and the exported controllers), so the fit cannot wait for a job:
:func:`calibrated` runs it when the workflow is planned (:func:`hubbeam.pipeline.plan.build_plan`)
and when a study is loaded in Python (:func:`hubbeam.api.load`), after the one check of the
configuration (:func:`hubbeam.check.check_configuration`) accepted the section. The fit is kept in
the study's ``identification/`` folder:

* ``fit.nc``: the fit (:func:`hubbeam.identification.dataset.fit_dataset`), with the global attribute
  ``inputs_fingerprint``, a SHA-256 of everything the fit depends on: the section, the identified
  case, the beam and the numerics as configured, the bytes of every experiment file and the
  sources of the code that fits (:func:`inputs_fingerprint`);
* ``fitted.yaml``: the fitted plant as the configuration fragment that gives the cases of
  ``apply_to`` (the identified case without one) its values
  (:func:`hubbeam.identification.section.fitted_fragment`); merged onto the study, it gives the
  records the workflow runs.

Both are written atomically. When ``fit.nc`` holds the fingerprint of the current inputs, its
values are read back instead of fitting again; editing the section, a data file, the case or the
fitting code fits again. The configuration with the fragment merged is checked again by the one
check, so a fitted plant the cases cannot run is refused like any configuration.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from collections.abc import Callable, Mapping
from pathlib import Path

import xarray as xr
import yaml

from hubbeam.check import CheckedConfiguration, check_configuration
from hubbeam.configuration.load import ConfigError, merge_configs
from hubbeam.identification import dataset, section
from hubbeam.identification.parameters import ParameterError
from hubbeam.identification.plant import CasePlant
from hubbeam.reporting.sourcedeps import script_dependencies
from hubbeam.results.io import write_netcdf, write_text
from hubbeam.results.paths import StudyPaths

#: the global attribute of ``fit.nc`` that records its inputs
FINGERPRINT = "inputs_fingerprint"


def inputs_fingerprint(checked: CheckedConfiguration) -> str:
    """A SHA-256 (hex) of what the fit of ``checked``'s ``identify`` section depends on (module
    docstring)."""
    entry = checked.config["identify"]
    settings = checked.settings
    digest = hashlib.sha256()
    digest.update(json.dumps({key: value for key, value in entry.items() if key != "apply_to"},
                             sort_keys=True, default=str).encode())
    digest.update(repr((settings.case(entry["case"]), settings.beam, settings.numerics)).encode())
    for name, experiment in sorted(entry["experiments"].items()):
        digest.update(name.encode() + Path(checked.base_dir, experiment["file"]).read_bytes())
    for source in script_dependencies(Path(section.__file__), extra_modules=[dataset.__name__]):
        digest.update(source.read_bytes())
    return digest.hexdigest()


def stored_values(path: Path, fingerprint: str) -> dict[str, float] | None:
    """The fitted values of the fit ``path`` when it was made from the inputs ``fingerprint``; None
    when there is no such file, or it was made from other inputs."""
    if not path.is_file():
        return None
    with xr.open_dataset(path) as fit:
        if fit.attrs.get(FINGERPRINT) != fingerprint:
            return None
        return {str(key): float(value) for key, value in zip(fit["parameter"].values, fit["value"].values)}


def fit_section(checked: CheckedConfiguration, paths: StudyPaths, fingerprint: str,
                say: Callable[[str], None]) -> dict[str, float]:
    """Run the fit of ``checked``'s ``identify`` section and write ``fit.nc`` and ``fitted.yaml``
    into ``paths``' identification folder; the fitted values by key."""
    entry, settings = checked.config["identify"], checked.settings
    plant = CasePlant(settings.case(entry["case"]), settings.beam, settings.numerics)
    say(f"identify: fitting {len(entry['parameters'])} parameters of case {entry['case']} to "
        f"{', '.join(settings.identify.fitted)} ...")
    result, experiments = section.identify(entry, plant, os.path.relpath(checked.base_dir))
    fit = dataset.fit_dataset(result, experiments)
    fit.attrs[FINGERPRINT] = fingerprint
    values = result.values
    fragment = section.fitted_fragment(entry, values, settings)
    header = ("# The plant fitted by the identify section (fit.nc beside this file has the intervals);\n"
              "# merged onto the configuration, it gives these values to the cases below.\n")
    write_netcdf(fit, paths.identification_fit())
    write_text(paths.identified_plant(), header + yaml.safe_dump(fragment, sort_keys=False))
    say(f"identify: cost {result.cost:.4g} after {result.evaluations} evaluations, {result.seconds:.1f} s; "
        f"-> {paths.identification_fit()}")
    return values


def calibrated(checked: CheckedConfiguration, paths: StudyPaths,
               say: Callable[[str], None] = lambda text: print(text, file=sys.stderr)) -> CheckedConfiguration:
    """``checked`` with its ``identify`` section fitted (module docstring): the same configuration
    without the section or without ``apply_to``, else the configuration whose ``apply_to`` cases
    run the fitted values, checked again. ``say`` reports a fit's progress."""
    entry = checked.config.get("identify")
    if not isinstance(entry, Mapping):
        return checked
    fingerprint = inputs_fingerprint(checked)
    values = stored_values(Path(paths.identification_fit()), fingerprint)
    if values is None:
        values = fit_section(checked, paths, fingerprint, say)
    if not section.applied_cases(entry):
        return checked
    try:
        fragment = section.fitted_fragment(entry, values, checked.settings)
    except ParameterError as error:
        raise ConfigError([f"identify.apply_to: the fitted plant cannot be run: {error}"], checked.files) from None
    return check_configuration(merge_configs(checked.config, fragment), checked.files)


__all__ = ["FINGERPRINT", "calibrated", "inputs_fingerprint", "stored_values"]
