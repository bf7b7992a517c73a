"""Load and validate the study configuration (``config/config.yaml``).

Validation has two layers, reported together in one :class:`ConfigError`:

1. the JSON schema ``workflow/schemas/config.schema.yaml`` (shape, types, ranges, allowed names);
2. checks a schema cannot express: the tip mass lies on the beam (``0 <= l <= L``), every case
   spans at least one output step, grids increase, numbers are finite, case names stay distinct
   on case-insensitive file systems, keys are text, and no YAML file repeats a key; a beam is
   either uniform or given by stations (``beam.sections``, from x = 0 to x = L), tables of
   stations and times increase, a maneuver or damping has only the keys of its kind, and a study
   (``study`` section) neither takes a folder of the paper's products nor compares unknown cases.

Every problem names the key path (``cases.fig05_tlam.maneuver.wf``), the offending value and
what is allowed. :func:`case_settings` resolves one case with the defaults of ``numerics``.
"""

from __future__ import annotations

import copy
import itertools
import json
import math
import os
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any, NamedTuple

import jsonschema
import yaml

from hubbeam import limits
from hubbeam.study import PAPER_FOLDERS

SCHEMA_PATH = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / "config.schema.yaml"

_TYPE_NAMES = {bool: "boolean", int: "integer", float: "decimal number", str: "text", dict: "mapping",
               list: "list", type(None): "null"}


class Problem(NamedTuple):
    """One configuration problem: the dotted key path and what is wrong there."""

    path: str
    text: str

    def __str__(self) -> str:
        return f"{self.path}: {self.text}"


class ConfigError(ValueError):
    """The configuration is invalid; ``problems`` lists every problem found."""

    def __init__(self, problems: Iterable[Problem], sources: Iterable[os.PathLike | str] = ()):
        self.problems = list(problems)
        names = ", ".join(str(source) for source in sources)
        where = f" ({names})" if names else ""
        count = f"{len(self.problems)} problems" if len(self.problems) > 1 else "1 problem"
        lines = "\n".join(f"  - {problem}" for problem in self.problems)
        super().__init__(f"invalid hubbeam configuration{where}, {count}:\n{lines}")


_RTOL_BOUND = {"minimum": limits.MIN_RTOL}
#: schema node (keys from the root) -> the bounds of :mod:`hubbeam.limits` filled in at load time;
#: the schema file states none of these numbers itself
SCHEMA_LIMITS = {
    ("$defs", "modes"): {"minimum": limits.MIN_MODES, "maximum": limits.MAX_MODES},
    ("properties", "numerics", "properties", "quadrature_points"):
        {"minimum": limits.MIN_QUADRATURE_POINTS, "maximum": limits.MAX_QUADRATURE_POINTS},
    ("properties", "numerics", "properties", "rtol"): _RTOL_BOUND,
    ("properties", "sweeps", "properties", "numerics", "properties", "rtol"): _RTOL_BOUND,
}


def read_schema(path: os.PathLike | str, bounds: Mapping[tuple, Mapping] | None = None) -> dict:
    """The JSON schema (YAML) at ``path`` with ``bounds`` ({node keys: bounds}, e.g.
    :data:`SCHEMA_LIMITS`) filled in; a clear error when the file is missing."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(
            f"the config schema {path} is missing: hubbeam runs from its source tree "
            "(install it with `pip install -e .`)"
        )
    schema = yaml.safe_load(path.read_text(encoding="utf-8"))
    for keys, values in (bounds or {}).items():
        node = schema
        for key in keys:
            node = node[key]
        node.update(values)
    return schema


SCHEMA = read_schema(SCHEMA_PATH, SCHEMA_LIMITS)
#: Case names double as wildcards and file names (``results/simulations/<case>.nc``).
CASE_NAME_PATTERN = SCHEMA["properties"]["cases"]["propertyNames"]["pattern"].strip("^$")

# "integer" means a YAML integer: 5.0 is rejected rather than silently used as an array size.
_VALIDATOR_CLASS = jsonschema.validators.extend(
    jsonschema.Draft202012Validator,
    type_checker=jsonschema.Draft202012Validator.TYPE_CHECKER.redefine(
        "integer", lambda _checker, value: isinstance(value, int) and not isinstance(value, bool)
    ),
)


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


def validate_config(cfg: Any, files: Iterable[os.PathLike | str] = ()) -> dict:
    """Check ``cfg`` against the schema and the physical constraints; return it unchanged.

    ``files`` are the files ``cfg`` was merged from (in Snakemake, ``workflow.configfiles``); they
    are re-read only to detect repeated keys, which YAML loaders silently resolve (last one wins).
    Raises :class:`ConfigError` listing every problem.
    """
    files = list(files)
    problems = [problem for path in files for problem in _read_file(Path(path))[1]]
    return _validate(cfg, problems, files)


def case_names(cfg: Mapping) -> list[str]:
    """Names of the configured cases, sorted."""
    return sorted(cfg["cases"])


def case_settings(cfg: Mapping, name: str) -> dict:
    """The fully resolved case ``name`` of a validated config (JSON-serialisable).

    Defaults: ``modes`` is ``numerics.modes``; without ``tip_mass`` the case has mass 0 at the tip;
    a tip mass given without ``position`` sits at the tip, ``position = beam.length``.
    """
    cases = cfg["cases"]
    if name not in cases:
        raise ConfigError([Problem(f"cases.{name}", f"unknown case; defined: {', '.join(sorted(cases))}")])
    case = cases[name]
    tip_mass = case.get("tip_mass", {})
    settings = {
        "name": name,
        "model": case["model"],
        "maneuver": _floats(case["maneuver"]),
        "t_end": float(case["t_end"]),
        "modes": int(case.get("modes", cfg["numerics"]["modes"])),
        "tip_mass": {
            "mass": float(tip_mass.get("mass", 0.0)),
            "position": float(tip_mass.get("position", cfg["beam"]["length"])),
        },
    }
    if "damping" in case:
        settings["damping"] = _floats(case["damping"])
    return settings


def _floats(entry: Mapping) -> dict:
    """A plain copy of a maneuver or damping entry with every number (also in lists and nested
    entries such as a pd reference) as float; the ``kind`` texts stay."""
    def plain(value):
        if isinstance(value, Mapping):
            return {key: plain(item) for key, item in value.items()}
        if isinstance(value, (list, tuple)):
            return [plain(item) for item in value]
        return value if isinstance(value, str) else float(value)
    return plain(entry)


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
        return {}, [Problem(label, f"got {_show(data)}; allowed: a mapping of keys at the top level")]
    return data, _repeated_keys(root, [], path)


def _repeated_keys(node: yaml.Node, parts: list, filename: Path) -> list[Problem]:
    problems = []
    if isinstance(node, yaml.MappingNode):
        first_line: dict[str, int] = {}
        for key_node, value_node in node.value:
            key = str(key_node.value)
            line = key_node.start_mark.line + 1
            if key in first_line:
                problems.append(Problem(_path(parts + [key]), f"repeated key in {filename} (lines "
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


def _validate(cfg: Any, problems: list[Problem], sources: list, section: Section | None = None) -> dict:
    schema = SCHEMA if section is None else _with_section(section)
    found = [problem for error in _VALIDATOR_CLASS(schema).iter_errors(cfg) for problem in _explain(error, schema)]
    found += _physical_problems(cfg)
    if section is not None and not found:
        found += section.check(cfg)
    problems = list(dict.fromkeys(problems + sorted(found, key=lambda problem: problem.path)))
    if problems:
        raise ConfigError(problems, sources)
    return cfg


def _with_section(section: Section) -> dict:
    """The study schema with ``section`` as one more required top-level key."""
    return {**SCHEMA, "required": [*SCHEMA["required"], section.name],
            "properties": {**SCHEMA["properties"], section.name: section.schema}}


def _explain(error: jsonschema.ValidationError, schema: dict) -> list[Problem]:
    """Turn one schema error into problems that name key, value and what is allowed."""
    parts = list(error.absolute_path)
    kind, instance = error.validator, error.instance
    if "propertyNames" in error.absolute_schema_path:
        return [Problem(_path(parts + [instance]),
                        f"illegal case name {instance!r}; allowed: letters, digits, '_' and '-' "
                        f"(pattern {CASE_NAME_PATTERN}), as the name becomes a file name")]
    if kind == "required":
        why = f"required when kind is {instance.get('kind')!r}" if "then" in error.absolute_schema_path else "required"
        return [Problem(_path(parts + [key]), f"missing ({why}); allowed: {_allowed(parts + [key], schema)}")
                for key in error.validator_value if key not in instance]
    if kind == "not":  # a maneuver key that belongs to the other kind
        allowed_keys = ", ".join(["kind", *error.schema["required"]])
        return [Problem(_path(parts + [key]), f"got {_show(instance[key])}; not allowed when kind is "
                        f"{instance['kind']!r} (allowed keys: {allowed_keys})")
                for key in error.validator_value["required"]]
    if kind == "additionalProperties":
        known = error.schema.get("properties", {})
        return [Problem(_path(parts + [key]), f"unknown key (value {_show(instance[key])}); allowed keys "
                        f"here: {', '.join(known)}") for key in instance if key not in known]
    if kind == "minProperties":
        return [Problem(_path(parts), "got no entries; allowed: at least one case")]
    if kind == "uniqueItems":
        return [Problem(_path(parts), f"got {_show(instance)}; allowed: distinct values")]
    got = f"got {_show(instance)}"
    if kind == "type":
        got += f" ({_type_name(instance)})"
        if isinstance(instance, str) and _parses_as_float(instance):
            got += (", as YAML 1.1 reads an exponent form without a decimal point and a signed exponent "
                    "as text (write 2.7667e+3 or 1.0e-9, not 2.7667e3 or 1e-9)")
    return [Problem(_path(parts), f"{got}; allowed: {_allowed(parts, schema)}")]


def _physical_problems(cfg: Any) -> list[Problem]:
    """Checks the schema cannot express; each runs only on values the schema accepted."""
    if not isinstance(cfg, dict):
        return []
    problems = _non_finite_numbers_and_non_text_keys(cfg, [])
    beam, numerics, eigen, cases = (_section(cfg, key) for key in ("beam", "numerics", "eigen", "cases"))
    # bounds derived from a length or step the schema rejects would only repeat that problem
    length = _positive(beam.get("length"))
    output_step = _positive(numerics.get("output_step"))

    max_steps, step_warning = _integer(numerics.get("max_steps")), _integer(numerics.get("step_warning"))
    if max_steps is not None and step_warning is not None and step_warning > max_steps:
        problems.append(Problem("numerics.step_warning",
                                f"got {step_warning}; allowed: at most numerics.max_steps = {max_steps}"))

    for grid_name in ("speeds", "positions"):
        grid = _section(eigen, grid_name)
        start, stop = _number(grid.get("start")), _number(grid.get("stop"))
        if start is not None and stop is not None and stop <= start:
            problems.append(Problem(f"eigen.{grid_name}.stop",
                                    f"got {stop}; allowed: a value > eigen.{grid_name}.start = {start}"))
        if grid_name == "positions" and stop is not None and length is not None and stop > length:
            problems.append(Problem("eigen.positions.stop",
                                    f"got {stop}; allowed: a position on the beam, <= beam.length = {length}"))

    first_spelling: dict[str, str] = {}
    for name, case in cases.items():
        if isinstance(name, str):
            other = first_spelling.setdefault(name.lower(), name)
            if other != name:
                problems.append(Problem(f"cases.{name}", f"case name {name!r} differs from {other!r} only in "
                                        "letter case; allowed: names distinct ignoring case (they are file names)"))
        if not isinstance(case, dict):
            continue
        t_end = _number(case.get("t_end"))
        if t_end is not None and output_step is not None and t_end < output_step:
            problems.append(Problem(f"cases.{name}.t_end", f"got {t_end}; allowed: at least one output step, "
                                    f"t_end >= numerics.output_step = {output_step}"))
        position = _number(_section(case, "tip_mass").get("position"))
        if position is not None and length is not None and position > length:
            problems.append(Problem(f"cases.{name}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
        problems += _case_entry_problems(f"cases.{name}", case)
    problems += _beam_problems(beam, length)
    problems += _study_problems(cfg, eigen, cases)
    problems += _sweep_problems(_section(cfg, "sweeps"), length)
    problems += _validation_problems(_section(cfg, "validation"), length, output_step)
    return problems


#: maneuver parameters of each kind (a sweep gives each of the first two kinds either fixed or swept)
MANEUVER_PARAMETERS = {"prescribed": ("wf", "tf"), "torque": ("tau_max", "tf"),
                       "speed_table": ("time", "speed"), "torque_table": ("time", "torque"),
                       "pd": ("kp", "kd", "reference")}
#: parameters of each kind of a pd maneuver's reference motion
REFERENCE_PARAMETERS = {"prescribed": ("wf", "tf"), "angle_table": ("time", "angle")}
#: parameters of each kind of damping
DAMPING_PARAMETERS = {"modal": ("axial", "transverse"),
                      "rayleigh": ("mass_coefficient", "stiffness_coefficient")}
#: beam keys of a uniform beam, replaced by ``sections`` for a non-uniform one
UNIFORM_BEAM_KEYS = ("density", "area", "youngs_modulus", "second_moment")


def _kind_problems(where: str, entry: Mapping, parameters: Mapping[str, tuple]) -> list[Problem]:
    """Keys of ``entry`` that do not belong to its ``kind`` (the schema checks the required ones)."""
    allowed = parameters.get(entry.get("kind"))
    if allowed is None:
        return []
    return [Problem(f"{where}.{key}", f"got {_show(value)}; not allowed when kind is "
                    f"{entry['kind']!r} (allowed keys: {', '.join(['kind', *allowed])})")
            for key, value in entry.items() if key not in ("kind", *allowed)]


def _table_problems(where: str, entry: Mapping, abscissa: str, columns: tuple[str, ...],
                    unit: str) -> list[Problem]:
    """A table's abscissa strictly increases and every column has its length."""
    first = entry.get(abscissa)
    if not isinstance(first, list) or any(_number(v) is None for v in first):
        return []  # the schema reports it
    problems = [Problem(f"{where}.{abscissa}", f"got {_show(first)}; allowed: strictly increasing "
                        f"values ({unit})")] if any(b <= a for a, b in itertools.pairwise(first)) else []
    for column in columns:
        values = entry.get(column)
        if isinstance(values, list) and len(values) != len(first):
            problems.append(Problem(f"{where}.{column}", f"got {len(values)} values; allowed: one "
                                    f"per entry of {where}.{abscissa} ({len(first)})"))
    return problems


def _case_entry_problems(where: str, case: Mapping) -> list[Problem]:
    """The maneuver, its pd reference and the damping have only their kind's keys; time tables
    start at t >= 0 and increase."""
    maneuver, damping = _section(case, "maneuver"), _section(case, "damping")
    problems = _kind_problems(f"{where}.maneuver", maneuver, MANEUVER_PARAMETERS)
    problems += _kind_problems(f"{where}.damping", damping, DAMPING_PARAMETERS)
    reference = _section(maneuver, "reference")
    problems += _kind_problems(f"{where}.maneuver.reference", reference, REFERENCE_PARAMETERS)
    for path, entry, kinds in ((f"{where}.maneuver", maneuver, MANEUVER_PARAMETERS),
                               (f"{where}.maneuver.reference", reference, REFERENCE_PARAMETERS)):
        columns = kinds.get(entry.get("kind"), ())
        if "time" not in columns:
            continue
        problems += _table_problems(path, entry, "time", columns[1:], "s")
        start = _number((entry.get("time") or [None])[0]) if isinstance(entry.get("time"), list) else None
        if start is not None and start < 0:
            problems.append(Problem(f"{path}.time", f"starts at {start}; allowed: times >= 0 s"))
    return problems


def _beam_problems(beam: Mapping, length: float | None) -> list[Problem]:
    """A beam is uniform (all of UNIFORM_BEAM_KEYS) or given by stations from 0 to L, not both."""
    if "sections" not in beam:
        return [Problem(f"beam.{key}", f"missing (required for a uniform beam, i.e. without "
                        f"beam.sections); allowed: {_allowed(['beam', key], SCHEMA)}")
                for key in UNIFORM_BEAM_KEYS if key not in beam]
    problems = [Problem(f"beam.{key}", f"got {_show(beam[key])}; not allowed together with "
                        "beam.sections (allowed: either the uniform keys or sections)")
                for key in UNIFORM_BEAM_KEYS if key in beam]
    sections = _section(beam, "sections")
    problems += _table_problems("beam.sections", sections, "x", ("rhoA", "EI", "EA"), "m")
    x = sections.get("x")
    if isinstance(x, list) and x and all(_number(v) is not None for v in x):
        if x[0] != 0:
            problems.append(Problem("beam.sections.x", f"starts at {x[0]}; allowed: the first "
                                    "station at the root, x = 0"))
        if length is not None and abs(x[-1] - length) > 1e-9 * length:
            problems.append(Problem("beam.sections.x", f"ends at {x[-1]}; allowed: the last "
                                    f"station at the tip, x = beam.length = {length}"))
    return problems


def _study_problems(cfg: Mapping, eigen: Mapping, cases: Mapping) -> list[Problem]:
    """A study keeps out of the paper's folders, compares its own cases and ends its eigen grid of
    positions at the tip; the paper (no ``study``) needs ``eigen.table2_speed`` for Table 2."""
    if "study" not in cfg:
        if "table2_speed" in eigen or not eigen:
            return []
        return [Problem("eigen.table2_speed", "missing (required for the paper's Table 2, i.e. "
                        f"without a study section); allowed: {_allowed(['eigen', 'table2_speed'], SCHEMA)}")]
    study = _section(cfg, "study")
    problems = []
    if study.get("name") in PAPER_FOLDERS:
        problems.append(Problem("study.name", f"got {study['name']!r}, a folder of the paper's "
                                f"products in results/; allowed: any other name ({', '.join(PAPER_FOLDERS)} "
                                "are taken)"))
    stop, length = _number(_section(eigen, "positions").get("stop")), _positive(_section(cfg, "beam").get("length"))
    if stop is not None and length is not None and stop < length:
        problems.append(Problem("eigen.positions.stop", f"got {stop}; allowed: beam.length = {length} "
                                "for a study (its Campbell diagram marks the critical speed with the "
                                "tip mass at the tip)"))
    for name, members in _section(study, "comparisons").items():
        for index, case in enumerate(members if isinstance(members, list) else []):
            if isinstance(case, str) and case not in cases:
                problems.append(Problem(f"study.comparisons.{name}[{index}]", f"got {case!r}; allowed: "
                                        f"a name of cases ({', '.join(sorted(map(str, cases)))})"))
    return problems


def _sweep_problems(sweeps: Mapping, length: float | None) -> list[Problem]:
    """A sweep's grids increase, and its fixed and swept parameters complete the maneuver and the
    tip mass without overlapping; the figure compares models of the sweep."""
    problems = []
    for name, spec in _section(sweeps, "maps").items():
        if not isinstance(spec, dict):
            continue
        where = f"sweeps.maps.{name}"
        grid = _section(spec, "grid")
        for key in grid:
            axis = _section(grid, key)
            start, stop = _number(axis.get("start")), _number(axis.get("stop"))
            if start is not None and stop is not None and stop <= start:
                problems.append(Problem(f"{where}.grid.{key}.stop", f"got {stop}; allowed: a value > "
                                        f"{where}.grid.{key}.start = {start}"))
            if key in ("wf", "tf", "tau_max") and start is not None and start <= 0:
                problems.append(Problem(f"{where}.grid.{key}.start", f"got {start}; allowed: a value > 0"))
            if key == "tip_position" and stop is not None and length is not None and stop > length:
                problems.append(Problem(f"{where}.grid.tip_position.stop", f"got {stop}; allowed: a "
                                        f"position on the beam, <= beam.length = {length}"))
        maneuver = _section(spec, "maneuver")
        needed = MANEUVER_PARAMETERS.get(maneuver.get("kind"))
        if needed is not None:
            for key in ("wf", "tf", "tau_max"):
                fixed, swept = key in maneuver, key in grid
                if key not in needed and swept:
                    problems.append(Problem(f"{where}.grid.{key}", f"swept, but kind is {maneuver['kind']!r}; "
                                            f"allowed parameters: {', '.join(needed)}"))
                elif key not in needed and fixed:
                    problems.append(Problem(f"{where}.maneuver.{key}",
                                            f"got {_show(maneuver[key])}; not allowed when kind is "
                                            f"{maneuver['kind']!r}; allowed keys: kind, {', '.join(needed)}"))
                elif key in needed and fixed == swept:
                    problems.append(Problem(f"{where}.maneuver.{key}",
                                            ("given both here and under grid" if fixed else "missing")
                                            + f"; allowed: exactly one of {where}.maneuver.{key} or "
                                            f"{where}.grid.{key}"))
        tip = _section(spec, "tip_mass")
        for key, grid_key in (("mass", "tip_mass"), ("position", "tip_position")):
            if key in tip and grid_key in grid:
                problems.append(Problem(f"{where}.tip_mass.{key}", f"given, but {grid_key} is swept; "
                                        f"allowed: either {where}.tip_mass.{key} or {where}.grid.{grid_key}"))
        position = _number(tip.get("position"))
        if position is not None and length is not None and position > length:
            problems.append(Problem(f"{where}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
        models = spec.get("models") if isinstance(spec.get("models"), list) else []
        figure = _section(spec, "figure")
        for key in ("model", "reference"):
            if key in figure and figure[key] not in models:
                problems.append(Problem(f"{where}.figure.{key}",
                                        f"got {figure[key]!r}; allowed: one of {where}.models = {models}"))
        if "model" in figure and figure.get("model") == figure.get("reference"):
            problems.append(Problem(f"{where}.figure.reference",
                                    f"got {figure['reference']!r}; allowed: a model other than figure.model"))
    return problems


def is_multiple(value: float, step: float) -> bool:
    """``value`` is a whole number of ``step`` (to 1e-9 relative): the rule of the startup checks
    and of the Exudyn model (``hubbeam.validation.exudyn_model``), which relies on them."""
    ratio = value / step
    return abs(ratio - round(ratio)) <= 1e-9 * max(ratio, 1.0)


def _validation_problems(validation: Mapping, length: float | None,
                         output_step: float | None) -> list[Problem]:
    """The validation section's mode counts increase, its grids and steps fit the output grid,
    and a tip mass sits on a node of every Exudyn mesh it is simulated on."""
    problems = []
    published = _section(validation, "published")
    modes = published.get("modes")
    if isinstance(modes, list) and all(_integer(m) is not None for m in modes):
        if any(later <= earlier for earlier, later in zip(modes, modes[1:])):
            problems.append(Problem("validation.published.modes", f"got {modes}; allowed: increasing "
                                    "integers (the largest count is the result)"))
    gammas = _section(published, "gammas")
    start, stop = _number(gammas.get("start")), _number(gammas.get("stop"))
    if start is not None and stop is not None and stop <= start:
        problems.append(Problem("validation.published.gammas.stop",
                                f"got {stop}; allowed: a value > validation.published.gammas.start = {start}"))
    exudyn, convergence = _section(validation, "exudyn"), _section(validation, "convergence")
    if output_step is not None:
        steps = [("validation.exudyn.time_step", exudyn.get("time_step"))]
        time_steps = convergence.get("time_steps")
        if isinstance(time_steps, list):
            steps += [(f"validation.convergence.time_steps[{i}]", v) for i, v in enumerate(time_steps)]
        for where, value in steps:
            step = _positive(value)
            if step is not None and not is_multiple(output_step, step):
                problems.append(Problem(where, f"got {step}; allowed: a step that divides "
                                        f"numerics.output_step = {output_step} a whole number of times"))
    meshes = [("validation.exudyn.elements", _integer(exudyn.get("elements")))]
    elements = convergence.get("elements")
    study_meshes = [(f"validation.convergence.elements[{i}]", _integer(e))
                    for i, e in enumerate(elements)] if isinstance(elements, list) else []
    for name, case in _section(validation, "cases").items():
        if not isinstance(case, dict):
            continue
        where = f"validation.cases.{name}"
        t_end = _positive(case.get("t_end"))
        if t_end is not None and output_step is not None and not is_multiple(t_end, output_step):
            problems.append(Problem(f"{where}.t_end", f"got {t_end}; allowed: a multiple of "
                                    f"numerics.output_step = {output_step}"))
        tip = _section(case, "tip_mass")
        position, mass = _number(tip.get("position")), _number(tip.get("mass"))
        if position is None or length is None:
            continue
        if position > length:
            problems.append(Problem(f"{where}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
            continue
        if not mass:
            continue
        for mesh, count in meshes + (study_meshes if convergence.get("case") == name else []):
            if count is not None and count >= 1 and not is_multiple(position, length / count):
                problems.append(Problem(f"{where}.tip_mass.position", f"got {position}; allowed: a node "
                                        f"of the Exudyn mesh, a multiple of beam.length / {mesh} = "
                                        f"{length / count:g} m"))
    return problems


def _non_finite_numbers_and_non_text_keys(node: Any, parts: list) -> list[Problem]:
    problems = []
    if isinstance(node, dict):
        for key, value in node.items():
            if not isinstance(key, str):
                problems.append(Problem(_path(parts + [str(key)]), f"key {key!r} is read by YAML as {_type_name(key)}; "
                                        f"allowed: text keys (write \"{key}\")"))
            problems += _non_finite_numbers_and_non_text_keys(value, parts + [str(key)])
    elif isinstance(node, list):
        for index, item in enumerate(node):
            problems += _non_finite_numbers_and_non_text_keys(item, parts + [index])
    elif isinstance(node, float) and not math.isfinite(node):
        problems.append(Problem(_path(parts), f"got {node}; allowed: a finite number"))
    return problems


# ---------------------------------------------------------------------------------------------
# describing the schema and the values


def _schema_at(parts: list, schema: dict) -> dict:
    """The schema of the value at ``parts`` ($refs resolved, sibling keys kept), {} if none."""
    node = _resolve(schema, schema)
    for part in parts:
        if isinstance(part, int):
            node = node.get("items", {})
        elif part in node.get("properties", {}):
            node = node["properties"][part]
        elif isinstance(node.get("additionalProperties"), dict):
            node = node["additionalProperties"]
        else:
            return {}
        node = _resolve(node, schema)
    return node


def _resolve(node: dict, schema: dict) -> dict:
    if "$ref" not in node:
        return node
    target = schema
    for key in node["$ref"].removeprefix("#/").split("/"):
        target = target[key]
    return {**_resolve(target, schema), **{key: value for key, value in node.items() if key != "$ref"}}


def _allowed(parts: list, schema: dict) -> str:
    """What the schema allows at ``parts``, followed by the key's description."""
    node = _schema_at(parts, schema)
    text = _allowed_values(node)
    return f"{text} -- {node['description'].strip()}" if "description" in node else text


def _allowed_values(node: dict) -> str:
    if "enum" in node:
        return "one of " + ", ".join(map(str, node["enum"]))
    kind = node.get("type")
    if kind in ("number", "integer"):
        bounds = [f"{symbol} {node[key]}" for key, symbol in
                  (("minimum", ">="), ("exclusiveMinimum", ">"), ("maximum", "<="), ("exclusiveMaximum", "<"))
                  if key in node]
        return ("an integer" if kind == "integer" else "a number") + (" " + " and ".join(bounds) if bounds else "")
    if kind == "array":
        return f"a list of at least {node.get('minItems', 0)} distinct values, each {_allowed_values(node['items'])}"
    if kind == "object" and "properties" in node:
        return "a mapping with keys " + ", ".join(node["properties"])
    if kind == "object":
        return "a mapping"
    return json.dumps(node)


def _show(value: Any) -> str:
    if isinstance(value, (dict, list)) or value is None:
        text = json.dumps(value, default=str)
        return text if len(text) <= 80 else text[:77] + "..."
    return repr(value)


def _type_name(value: Any) -> str:
    return _TYPE_NAMES.get(type(value), type(value).__name__)


def _parses_as_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _path(parts: list) -> str:
    path = ""
    for part in parts:
        path += f"[{part}]" if isinstance(part, int) and not isinstance(part, bool) else f".{part}"
    return path.lstrip(".") or "<top level>"


def _section(mapping: Mapping, key: str) -> Mapping:
    value = mapping.get(key)
    return value if isinstance(value, dict) else {}


def _number(value: Any) -> float | None:
    """``value`` as float if it is a finite YAML number, else None (the schema reports it)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        return float(value)
    return None


def _positive(value: Any) -> float | None:
    """``value`` as float if it is a finite YAML number > 0, else None (the schema reports it)."""
    number = _number(value)
    return number if number is not None and number > 0.0 else None


def _integer(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None
