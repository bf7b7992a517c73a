"""Load and validate the study configuration (``config/config.yaml``).

Validation has two layers, reported together in one :class:`ConfigError`:

1. the JSON schema ``src/hubbeam/configuration/schemas/config.schema.yaml`` (shape, types, ranges, allowed names,
   the keys of each maneuver and damping kind);
2. checks a schema cannot express: the tip mass lies on the beam (``0 <= l <= L``), every case
   spans at least one output step, grids increase, numbers are finite, case names stay distinct
   on case-insensitive file systems, keys are text, and no YAML file repeats a key; a beam has
   the keys of one form only (the paper's factors, its products, or stations ``beam.sections``
   from x = 0 to x = L), tables of stations and times increase, a study
   (``study`` section) neither takes a folder of the paper's products nor compares unknown cases,
   and no case, validation run or sweep would need more memory than ``numerics.memory_budget_mb``
   (:mod:`hubbeam.results.variables`).

Before validation, text that reads as a finite number where the schema wants a number is taken
as that number (:func:`coerce_numbers`): YAML 1.1 reads ``1e-9`` as text, and the ``numerics``
keys left out take their defaults; after it, the ``eigen`` grids left out are derived from the
study (:mod:`hubbeam.configuration.defaults`). The configuration is completed in place.

Every problem names the key path (``cases.fig05_tlam.maneuver.wf``), the offending value and
what is allowed. :mod:`hubbeam.configuration.settings` turns a checked configuration into the
frozen objects everything downstream takes.
"""

from __future__ import annotations

import copy
import os
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any, NamedTuple

import yaml

from hubbeam.configuration.checks import physical_problems
from hubbeam.configuration.defaults import fill_eigen, fill_linear, fill_numerics
from hubbeam.configuration.grids import expand_case_grids
from hubbeam.configuration.schema import (
    SCHEMA,
    Problem,
    Validator,
    coerce_numbers,
    explain,
    key_path,
    show,
)


class ConfigError(ValueError):
    """The configuration is invalid; ``problems`` lists every problem found."""

    def __init__(self, problems: Iterable[Problem], sources: Iterable[os.PathLike | str] = ()):
        self.problems = list(problems)
        names = ", ".join(str(source) for source in sources)
        where = f" ({names})" if names else ""
        count = f"{len(self.problems)} problems" if len(self.problems) > 1 else "1 problem"
        lines = "\n".join(f"  - {problem}" for problem in self.problems)
        super().__init__(f"invalid hubbeam configuration{where}, {count}:\n{lines}")


class Section(NamedTuple):
    """A top-level section checked on top of the study schema (a tool's own settings, such as
    the benchmark's): its JSON ``schema``, which may refer to the study schema's ``$defs``, and
    ``check(cfg)``, the problems a schema cannot express (run once the schema accepts ``cfg``)."""

    name: str
    schema: dict
    check: Callable[[dict], list[Problem]]


# ---------------------------------------------------------------------------------------------
# public API


def read_config_file(path: os.PathLike | str) -> dict:
    """Read one YAML (or JSON) config file, rejecting repeated keys and non-mapping content."""
    data, problems = _read_file(Path(path))
    if problems:
        raise ConfigError(problems, [path])
    return data


def merge_configs(*configs: Mapping) -> dict:
    """Merge configs left to right like Snakemake: mappings recursively, anything else replaced."""
    merged: dict = {}
    for config in configs:
        _update(merged, copy.deepcopy(dict(config)))
    return merged


def load_config(paths: os.PathLike | str | Iterable[os.PathLike | str],
                section: Section | None = None) -> dict:
    """Read, merge (later files override earlier ones) and validate one or several config files;
    ``section`` adds a required top-level section of its own schema and checks."""
    paths = [paths] if isinstance(paths, (str, os.PathLike)) else list(paths)
    contents, problems = [], []
    for path in paths:
        data, file_problems = _read_file(Path(path))
        contents.append(data)
        problems += file_problems
    return _validate(merge_configs(*contents), problems, paths, section)


def check_schema(cfg: Any, files: Iterable[os.PathLike | str] = ()) -> dict:
    """Check ``cfg`` against the schema and the physical constraints; return it, completed.

    This is the first stage of the one check of a configuration,
    :func:`hubbeam.check.check_configuration`, which the workflow and :func:`hubbeam.api.load`
    call: it does not resolve what needs the cases' matrices (designs, sampled controllers,
    shapers), the ``control`` section or the readings, so a configuration it accepts may still be
    refused there.

    Numbers YAML read as text (``1e-9``) are converted in ``cfg`` itself (:func:`coerce_numbers`),
    so that the config a workflow hands its rules holds floats.

    ``files`` are the files ``cfg`` was merged from (in Snakemake, ``workflow.configfiles``); they
    are re-read only to detect repeated keys, which YAML loaders silently resolve (last one wins).
    Raises :class:`ConfigError` listing every problem.
    """
    files = list(files)
    problems = [problem for path in files for problem in _read_file(Path(path))[1]]
    return _validate(cfg, problems, files)


def validate_parts(cfg: dict, schema: dict) -> dict:
    """Check ``cfg``, a configuration of some sections only, against ``schema`` (made of the
    study schema's sections) and the physical constraints; raise :class:`ConfigError` listing every
    problem. :mod:`hubbeam.configuration.settings` checks the Python API's bare case and numerics so."""
    return _validate(cfg, [], [], schema=schema)


# ---------------------------------------------------------------------------------------------
# reading files


def _read_file(path: Path) -> tuple[dict, list[Problem]]:
    """Parse ``path``; return its mapping (empty when unusable) and the problems found."""
    label = f"file {path}"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        return {}, [Problem(label, f"cannot be read ({error.strerror or error}); allowed: a readable YAML file")]
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
        data = yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        line = f" at line {mark.line + 1}" if mark else ""
        return {}, [Problem(label, f"is not valid YAML{line}: {getattr(error, 'problem', None) or error}")]
    if not isinstance(data, dict):
        return {}, [Problem(label, f"got {show(data)}; allowed: a mapping of keys at the top level")]
    return data, _repeated_keys(root, [], path)


def _repeated_keys(node: yaml.Node, parts: list, filename: Path) -> list[Problem]:
    problems = []
    if isinstance(node, yaml.MappingNode):
        first_line: dict[str, int] = {}
        for key_node, value_node in node.value:
            key = str(key_node.value)
            line = key_node.start_mark.line + 1
            if key in first_line:
                problems.append(Problem(key_path(parts + [key]), f"repeated key in {filename} (lines "
                                        f"{first_line[key]} and {line}); allowed: each key once per mapping"))
            else:
                first_line[key] = line
            problems += _repeated_keys(value_node, parts + [key], filename)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            problems += _repeated_keys(item, parts + [index], filename)
    return problems


def _update(config: dict, override: Mapping) -> None:
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(config.get(key), dict):
            _update(config[key], value)
        else:
            config[key] = value


# ---------------------------------------------------------------------------------------------
# validation


def _validate(cfg: Any, problems: list[Problem], sources: list, section: Section | None = None,
              schema: dict | None = None) -> dict:
    whole = schema is None  # a whole configuration, not the API's bare case and numerics
    schema = schema or (SCHEMA if section is None else _with_section(section))
    if whole and isinstance(cfg, dict):
        problems = problems + expand_case_grids(cfg)
    coerce_numbers(cfg, schema)
    if isinstance(cfg, dict):
        fill_numerics(cfg)
    found = [problem for error in Validator(schema).iter_errors(cfg) for problem in explain(error, schema, cfg)]
    found += physical_problems(cfg, whole)
    if section is not None and not found:
        found += section.check(cfg)
    problems = list(dict.fromkeys(problems + sorted(found, key=lambda problem: problem.path)))
    if problems:
        raise ConfigError(problems, sources)
    if whole:
        fill_eigen(cfg)
        fill_linear(cfg)
    return cfg


def _with_section(section: Section) -> dict:
    """The study schema with ``section`` as one more required top-level key."""
    return {**SCHEMA, "required": [*SCHEMA["required"], section.name],
            "properties": {**SCHEMA["properties"], section.name: section.schema}}


# ---------------------------------------------------------------------------------------------
# describing the schema and the values


