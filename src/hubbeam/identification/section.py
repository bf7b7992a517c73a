"""The planned ``identify`` section of a study: its check before any job, and the fit it asks for.

A study calibrates one of its cases to a rig's experiments with (the configuration's schema has
the section; ``docs/identification.md`` describes it)::

    identify:
      case: rig                                  # the case whose parameters are fitted
      experiments:                               # name -> kind, file (relative to the config file), settings
        tap: {kind: modal, file: tap.csv, hub: held}
        ring: {kind: free_decay, file: ring.csv, lowpass: 10}   # a free oscillation: its logarithmic decrement
        frf: {kind: frequency_response, file: frf.csv, input: voltage, output: deflection_angle, averages: 4}
        pulse: {kind: time_series, file: pulse.csv, input: voltage, sensors: {hub_angle: {quantum: 0.0015}}}
      parameters:                                # configuration key -> bounds and an optional start
        root_spring.stiffness: {lower: 10, upper: 60, start: 30}
      fit: [tap, frf]                            # default: every experiment not held out
      validate: [pulse]                          # held out: predicted with the fitted values
      starts: 5                                  # starting points of the fit (default 5)
      seed: 0                                    # of the Latin hypercube of the starts (default 0)
      apply_to: [rig, rig_lqg]                   # the cases that run on the fitted values (default none)

:func:`identify_problems` checks such a section with only the names of the configuration's cases:
every experiment file read and checked (its problems name the file, line and column), every key a
parameter with ordered bounds and a start within them, the lists naming experiments; each message
starts with its key, ``identify.<...>``. What needs the cases' records (a root spring's key on a
case without one, a voltage without a drive, a mode beyond the case's, a case of ``apply_to`` that
cannot take a fitted value) is checked by :func:`case_problems` once the cases are built; both run
in the one check of the configuration (``hubbeam.check``). :func:`identify` runs the fit the
section asks for and returns its :class:`~hubbeam.identification.fit.FitResult` with the
experiments by name; :func:`fitted_fragment` is the fitted plant as the configuration fragment that
gives the cases of ``apply_to`` its values.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping
from pathlib import Path

from hubbeam.configuration.load import merge_configs
from hubbeam.configuration.settings import Settings
from hubbeam.configuration.tabular import TableError
from hubbeam.identification.experiments import (
    HUBS,
    INPUTS,
    NAME,
    SIGNALS,
    Experiment,
    PdLoop,
    TimeSeries,
    read_frequency_response,
    read_modal_test,
    read_time_series,
)
from hubbeam.identification.fit import FitResult, fit
from hubbeam.identification.parameters import (
    ParameterError,
    fragment,
    free_parameters,
    is_sensor,
    kind_of,
    nominal_value,
)
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import ExperimentMismatch, check_experiment
from hubbeam.identification.spectra import read_free_decay

#: the keys of each kind of experiment entry besides ``kind`` and ``file``
ENTRY_KEYS = {"modal": ("hub", "speed"),
              "free_decay": ("hub", "lowpass"),
              "frequency_response": ("input", "output", "averages", "hold", "sample_time"),
              "time_series": ("input", "excitation", "sensors", "loop", "hold")}
#: the keys of the section
SECTION_KEYS = ("case", "experiments", "parameters", "fit", "validate", "starts", "seed", "apply_to")
#: the starts of a fit unless the section says
DEFAULT_STARTS = 5


class SectionError(ValueError):
    """The ``identify`` section cannot be used; the message starts with the key."""


def read_entry(name: str, entry: Mapping, base_dir: os.PathLike | str) -> Experiment:
    """The experiment ``name`` of an ``identify.experiments`` entry (its file relative to
    ``base_dir``); a :class:`SectionError` naming ``identify.experiments.<name>.<key>``."""
    where = f"identify.experiments.{name}"
    if not isinstance(name, str) or not NAME.match(name):
        raise SectionError(f"{where}: not a name; allowed: letters, digits and '_', starting with a letter")
    if not isinstance(entry, Mapping):
        raise SectionError(f"{where} = {entry!r}; allowed: a mapping with kind and file")
    kind = entry.get("kind")
    if kind not in ENTRY_KEYS:
        raise SectionError(f"{where}.kind = {kind!r}; allowed: one of {', '.join(ENTRY_KEYS)}")
    unknown = sorted(set(entry) - {"kind", "file", *ENTRY_KEYS[kind]})
    if unknown:
        raise SectionError(f"{where}.{unknown[0]}: not a key of a {kind} experiment; allowed: kind, file, "
                           f"{', '.join(ENTRY_KEYS[kind])}")
    file = entry.get("file")
    if not isinstance(file, str) or not file:
        raise SectionError(f"{where}.file = {file!r}; allowed: the path of a CSV file relative to the config file")
    options = {key: value for key, value in entry.items() if key not in ("kind", "file")}
    path = Path(base_dir, file)
    try:
        if kind in ("modal", "free_decay"):
            if options.get("hub", "held") not in HUBS:
                raise SectionError(f"{where}.hub = {options['hub']!r}; allowed: one of {', '.join(HUBS)}")
            return (read_modal_test if kind == "modal" else read_free_decay)(path, name, **options)
        for key, allowed in (("input", INPUTS), ("output", SIGNALS)):
            if key in ENTRY_KEYS[kind] and (key == "input" or kind == "frequency_response") \
                    and options.get(key) not in allowed:
                raise SectionError(f"{where}.{key} = {options.get(key)!r}; allowed: one of {', '.join(allowed)}")
        if kind == "frequency_response":
            return read_frequency_response(path, name=name, **options)
        loop = options.pop("loop", None)
        if loop is not None:
            if not isinstance(loop, Mapping) or not {"kp"} <= set(loop) <= {"kp", "kd"}:
                raise SectionError(f"{where}.loop = {loop!r}; allowed: {{kp, kd}} (gains on the hub angle)")
            loop = PdLoop(**loop)
        return read_time_series(path, name=name, loop=loop, **options)
    except (TableError, ValueError, TypeError) as error:
        if isinstance(error, SectionError):
            raise
        at = "file" if isinstance(error, TableError) else "settings"
        raise SectionError(f"{where}.{at}: {error}") from None


def _names(section: Mapping, key: str, experiments: Iterable[str]) -> list[str]:
    names = section.get(key, [])
    if not isinstance(names, list) or not all(isinstance(name, str) for name in names):
        raise SectionError(f"identify.{key} = {names!r}; allowed: a list of experiment names")
    unknown = [name for name in names if name not in experiments]
    if unknown:
        raise SectionError(f"identify.{key}: {unknown[0]!r} is not an experiment; allowed: "
                           f"{', '.join(experiments) or 'the names of identify.experiments'}")
    return names


def _whole(section: Mapping, key: str, least: int, default: int) -> int:
    value = section.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise SectionError(f"identify.{key} = {value!r}; allowed: a whole number >= {least}")
    return value


def _parameter_problems(parameters, measured: set[str]) -> list[str]:
    if not isinstance(parameters, Mapping) or not parameters:
        return [f"identify.parameters = {parameters!r}; allowed: a mapping of at least one configuration key to "
                "{lower, upper, start}"]
    problems = []
    for key, entry in parameters.items():
        where = f"identify.parameters.{key}"
        try:
            kind = kind_of(key)
        except ParameterError as error:
            problems.append(f"identify.parameters.{error}")
            continue
        if key.startswith("sensors.") and key.split(".")[1] not in measured:
            problems.append(f"{where}: no time series measures {key.split('.')[1]}; allowed: the sensors of "
                            f"{', '.join(sorted(measured)) or 'no signal'}")
        if not isinstance(entry, Mapping) or not {"lower", "upper"} <= set(entry) or set(entry) - {
                "lower", "upper", "start"}:
            problems.append(f"{where} = {entry!r}; allowed: {{lower, upper}} with an optional start")
            continue
        numbers = {}
        for name, value in entry.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                problems.append(f"{where}.{name} = {value!r}; allowed: a finite number")
            else:
                numbers[name] = float(value)
        for name in ("lower", "upper"):
            if name in numbers and not kind.allows(numbers[name]):
                problems.append(f"{where}.{name} = {numbers[name]!r}; allowed: {kind.allowed()}")
        if {"lower", "upper"} <= set(numbers):
            lower, upper = numbers["lower"], numbers["upper"]
            if not lower < upper:
                problems.append(f"{where}: lower = {lower!r}, upper = {upper!r}; allowed: lower < upper")
            elif "start" in numbers and not lower <= numbers["start"] <= upper:
                problems.append(f"{where}.start = {numbers['start']!r}; allowed: a start in [{lower!r}, {upper!r}]")
    return problems


def identify_problems(section: Mapping, case_names: Iterable[str], base_dir: os.PathLike | str) -> list[str]:
    """Every problem of the ``identify`` ``section`` of a configuration whose cases are
    ``case_names`` and whose files lie relative to ``base_dir`` (module docstring); empty when it
    can be run."""
    if not isinstance(section, Mapping):
        return [f"identify = {section!r}; allowed: a mapping with {', '.join(SECTION_KEYS)}"]
    problems = [f"identify.{key}: not a key of the section; allowed: {', '.join(SECTION_KEYS)}"
                for key in section if key not in SECTION_KEYS]
    cases = list(case_names)
    if section.get("case") not in cases:
        problems.append(f"identify.case = {section.get('case')!r}; allowed: one of the cases {', '.join(cases)}")
    entries = section.get("experiments")
    found: dict[str, Experiment] = {}
    if not isinstance(entries, Mapping) or not entries:
        problems.append(f"identify.experiments = {entries!r}; allowed: a mapping of at least one name to an "
                        "experiment {kind, file, ...}")
        entries = {}
    for name, entry in entries.items():
        try:
            found[name] = read_entry(name, entry, base_dir)
        except SectionError as error:
            problems.append(str(error))
    measured = {signal for experiment in found.values() if isinstance(experiment, TimeSeries)
                for signal in experiment.signals}
    problems += _parameter_problems(section.get("parameters"), measured)
    try:
        fitted, held_out = _split(section, list(entries))
        if set(fitted) & set(held_out):
            problems.append(f"identify.validate: {sorted(set(fitted) & set(held_out))[0]!r} is also fitted; allowed: "
                            "experiments not in identify.fit")
    except SectionError as error:
        problems.append(str(error))
    for key, least in (("starts", 1), ("seed", 0)):
        try:
            _whole(section, key, least, 0 if key == "seed" else DEFAULT_STARTS)
        except SectionError as error:
            problems.append(str(error))
    applied = section.get("apply_to", [])
    if not isinstance(applied, list) or not all(isinstance(name, str) for name in applied):
        problems.append(f"identify.apply_to = {applied!r}; allowed: a list of case names")
    else:
        problems += [f"identify.apply_to: {name!r} is not a case; allowed: {', '.join(cases)}"
                     for name in applied if name not in cases]
    return problems


def applied_cases(section: Mapping) -> list[str]:
    """The cases that run on the fitted values (``identify.apply_to``)."""
    return list(section.get("apply_to", []))


def case_problems(section: Mapping, settings: Settings, base_dir: os.PathLike | str,
                  listed: Iterable[str]) -> list[str]:
    """The problems of a section :func:`identify_problems` accepts that need the cases' records
    (``settings``): the identified case must take every parameter and predict every experiment, and
    each case of ``apply_to`` must take every fitted value of the plant and be one of ``listed`` (the
    cases of the configuration's ``cases``, which a fragment can change; a grid's are made from its
    entry); a key of ``beam`` changes the beam every case runs, so with one ``apply_to`` names every
    case."""
    case = settings.case(section["case"])
    plant = CasePlant(case, settings.beam, settings.numerics)
    experiments = {name: read_entry(name, entry, base_dir) for name, entry in section["experiments"].items()}
    measured = [signal for experiment in experiments.values() if isinstance(experiment, TimeSeries)
                for signal in experiment.signals]
    problems = []
    try:
        free_parameters(section["parameters"], case, settings.beam, "identify.parameters", measured)
    except ParameterError as error:
        problems.append(str(error))
    for name, experiment in experiments.items():
        try:
            check_experiment(plant, experiment)
        except ExperimentMismatch as error:
            problems.append(f"identify.experiments.{name}: {error}")
    keys = [key for key in section["parameters"] if not is_sensor(key)]
    applied, listed = applied_cases(section), list(listed)
    for name in applied:
        if name not in listed:
            problems.append(f"identify.apply_to: {name!r} is a case of case_grids; allowed: a case of `cases` "
                            f"({', '.join(listed)})")
            continue
        for key in keys:
            try:
                nominal_value(key, settings.case(name), settings.beam)
            except ParameterError as error:
                problems.append(f"identify.apply_to: {name!r} cannot run the fitted {error}")
    beam_keys = [key for key in keys if key.startswith("beam.")]
    others = [name for name in settings.cases if name not in applied]
    if applied and beam_keys and others:
        problems.append(f"identify.apply_to = {applied!r}: the fitted {beam_keys[0]} changes the beam every case "
                        f"runs, but {others[0]!r} is not listed; allowed: every case ({', '.join(settings.cases)}), "
                        "or parameters of the cases only")
    return problems


def fitted_fragment(section: Mapping, values: Mapping[str, float], settings: Settings) -> dict:
    """The configuration fragment that puts the fitted plant ``values`` (key -> value) into the cases
    of ``apply_to`` (the identified case alone without one): each case's own sections with the
    values (:func:`hubbeam.identification.parameters.fragment`), the beam's fitted keys once."""
    names = applied_cases(section) or [section["case"]]
    return merge_configs(*(fragment(name, values, settings.case(name), settings.beam) for name in names))


def _split(section: Mapping, names: list[str]) -> tuple[list[str], list[str]]:
    """The fitted and the held-out experiments' names."""
    held_out = _names(section, "validate", names)
    fitted = _names(section, "fit", names) if "fit" in section else [n for n in names if n not in held_out]
    if not fitted:
        raise SectionError("identify.fit: no experiment; allowed: at least one experiment to fit")
    return fitted, held_out


def identify(section: Mapping, plant: CasePlant, base_dir: os.PathLike | str) -> tuple[FitResult, dict]:
    """The fit ``section`` asks for on ``plant`` (the case ``identify.case``): the
    :class:`~hubbeam.identification.fit.FitResult` and the experiments by name; a
    :class:`SectionError` or the fit's own refusal (the case cannot take a parameter or predict an
    experiment) at the first problem."""
    experiments = {name: read_entry(name, entry, base_dir) for name, entry in section["experiments"].items()}
    fitted, held_out = _split(section, list(experiments))
    measured = [signal for name in fitted if isinstance(experiments[name], TimeSeries)
                for signal in experiments[name].signals]
    parameters = free_parameters(section["parameters"], plant.case, plant.beam, "identify.parameters", measured)
    result = fit(plant, [experiments[name] for name in fitted], parameters,
                 starts=_whole(section, "starts", 1, DEFAULT_STARTS), seed=_whole(section, "seed", 0, 0),
                 validation=[experiments[name] for name in held_out])
    return result, experiments


__all__ = ["ENTRY_KEYS", "SectionError", "applied_cases", "case_problems", "fitted_fragment", "identify",
           "identify_problems", "read_entry"]
