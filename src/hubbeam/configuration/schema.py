"""The configuration schema and how its violations are told to the user.

The package data ``hubbeam/configuration/schemas/config.schema.yaml`` (JSON schema, draft 2020-12; found through
:mod:`importlib.resources`, so an installed package checks configurations too) describes the shape,
types, ranges and allowed names of a configuration. The bounds of :mod:`hubbeam.model.limits` are filled
into it when it is read (:data:`SCHEMA_LIMITS`), so the file states none of them. :func:`explain`
turns one schema error into :class:`Problem` entries that name the key path, the value found and
what is allowed; :func:`coerce_numbers` takes text that reads as a finite number for a number where
the schema wants one (YAML 1.1 reads ``1e-9`` as text). Each maneuver, reference and damping kind
has a branch of its own keys in the schema, selected by ``kind``; :func:`kind_keys` reads them.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any, NamedTuple

import jsonschema
import yaml

from hubbeam.model import limits
from hubbeam.model.models import DESIGN_ONLY_MODELS, MODELS

#: the schema, package data of hubbeam
SCHEMA_RESOURCE = resources.files("hubbeam.configuration") / "schemas" / "config.schema.yaml"


_TYPE_NAMES = {bool: "boolean", int: "integer", float: "decimal number", str: "text", dict: "mapping",
               list: "list", type(None): "null"}


class Problem(NamedTuple):
    """One configuration problem: the dotted key path and what is wrong there."""

    path: str
    text: str

    def __str__(self) -> str:
        return f"{self.path}: {self.text}"


_RTOL_BOUND = {"minimum": limits.MIN_RTOL}


_STEPS_BOUND = {"minimum": limits.MIN_STEPS}


#: schema node (keys from the root) -> the bounds of :mod:`hubbeam.model.limits` and the model names of
#: :data:`hubbeam.model.models.MODELS`, filled in at load time; the schema file states none of them itself
SCHEMA_LIMITS = {
    ("$defs", "model"): {"enum": list(MODELS)},
    ("$defs", "design_model"): {"enum": [*MODELS, *DESIGN_ONLY_MODELS]},
    ("$defs", "modes"): {"minimum": limits.MIN_MODES, "maximum": limits.MAX_MODES},
    ("properties", "numerics", "properties", "quadrature_points"):
        {"minimum": limits.MIN_QUADRATURE_POINTS, "maximum": limits.MAX_QUADRATURE_POINTS},
    ("properties", "numerics", "properties", "rtol"): _RTOL_BOUND,
    ("properties", "sweeps", "properties", "numerics", "properties", "rtol"): _RTOL_BOUND,
    ("properties", "numerics", "properties", "max_steps"): _STEPS_BOUND,
    ("properties", "sweeps", "properties", "numerics", "properties", "max_steps"): _STEPS_BOUND,
}


def read_schema(path, bounds: Mapping[tuple, Mapping] | None = None) -> dict:
    """The JSON schema (YAML) at ``path`` (a file or a :mod:`importlib.resources` traversable) with
    ``bounds`` ({node keys: bounds}, e.g. :data:`SCHEMA_LIMITS`) filled in; a clear error when the
    file is missing."""
    path = Path(path) if isinstance(path, (str, os.PathLike)) else path
    if not path.is_file():
        raise FileNotFoundError(f"the config schema {path} is missing: the hubbeam package is incomplete "
                                "(reinstall it with `pip install .`)")
    schema = yaml.safe_load(path.read_text(encoding="utf-8"))
    for keys, values in (bounds or {}).items():
        node = schema
        for key in keys:
            node = node[key]
        node.update(values)
    return schema


SCHEMA = read_schema(SCHEMA_RESOURCE, SCHEMA_LIMITS)


def kind_keys(definition: str) -> dict[str, tuple[str, ...]]:
    """The keys (besides ``kind``) of each kind of the ``$defs`` entry ``definition`` (``maneuver``,
    ``reference``, ``damping``), read from its per-kind branches: the one statement of them."""
    keys = {}
    for rule in SCHEMA["$defs"][definition]["allOf"]:
        kind = rule["if"]["properties"]["kind"]["const"]
        branch = _resolve(rule["then"], SCHEMA)
        keys[kind] = tuple(key for key in branch["properties"] if key != "kind")
    return keys


#: the measured signals a controller may feed back (``output_feedback``) or weight (an LQR design):
#: the linear models' outputs without feedthrough, as the schema's ``measured_signal`` lists them
MEASURED_SIGNALS = tuple(SCHEMA["$defs"]["measured_signal"]["enum"])


#: Case names double as wildcards and file names (``results/simulations/<case>.nc``).
CASE_NAME_PATTERN = SCHEMA["properties"]["cases"]["propertyNames"]["pattern"].strip("^$")


# "integer" means a YAML integer: 5.0 is rejected rather than silently used as an array size.
Validator = jsonschema.validators.extend(
    jsonschema.Draft202012Validator,
    type_checker=jsonschema.Draft202012Validator.TYPE_CHECKER.redefine(
        "integer", lambda _checker, value: isinstance(value, int) and not isinstance(value, bool)
    ),
)


def coerce_numbers(node: Any, schema: dict, parts: list | None = None, root: Any = None) -> None:
    """Replace, in place, every text in ``node`` that stands where ``schema`` wants a number and
    reads as a finite decimal number (``"1e-9"``, ``"2.7667e3"``, ``"2.0"``) by that number.

    YAML 1.1, the rules Snakemake reads configs with, takes an exponent form without a decimal
    point or without a signed exponent for text; converting it here, before validation, lets the
    rules receive floats. Other text (``"fast"``, ``"nan"``) stays and the schema rejects it.
    """
    parts, root = ([], node) if parts is None else (parts, root)
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in list(items):
        where = parts + [key]
        if isinstance(value, (dict, list)):
            coerce_numbers(value, schema, where, root)
        elif isinstance(value, str) and (number := _finite_float(value)) is not None \
                and _schema_at(where, schema, root).get("type") == "number":  # the schema's node only for number text
            node[key] = number


def _finite_float(text: str) -> float | None:
    """``text`` as a finite float, None if it is not one."""
    try:
        number = float(text)
    except ValueError:
        return None
    return number if math.isfinite(number) else None


def explain(error: jsonschema.ValidationError, schema: dict, root: Any = None) -> list[Problem]:
    """Turn one schema error into problems that name key, value and what is allowed; ``root`` is
    the validated instance (it selects the branch of a kind whose keys are described). Any error of
    the schema gets words: a rule without words of its own is told by what the schema allows at
    the key (:func:`allowed`)."""
    parts = list(error.absolute_path)
    kind, instance = error.validator, error.instance
    if "propertyNames" in error.absolute_schema_path:  # a name of a mapping: the instance is the name
        return [_name_problem(parts, error)]
    if kind == "pattern":
        return [Problem(key_path(parts), f"got {show(instance)}; allowed: {_pattern_words(error.validator_value)}")]
    branch = _branch_condition(error)
    if kind == "required" and isinstance(instance, dict):
        why = f"required {branch}" if branch else "required"
        return [Problem(key_path(parts + [key]), f"missing ({why}); allowed: {allowed(parts + [key], schema, root)}")
                for key in error.validator_value if key not in instance]
    if kind == "not" and isinstance(instance, dict):  # keys a branch forbids: not: {required: [...]} or
        negated = error.validator_value  # not: {anyOf: [{required: [...]}, ...]}
        forbidden = [key for rule in negated.get("anyOf", [negated]) for key in rule.get("required", [])]
        found = [Problem(key_path(parts + [key]), f"got {show(instance[key])}; not allowed {branch or 'here'}")
                 for key in forbidden if key in instance]
        if found:
            return found
    if kind == "not" and not isinstance(instance, dict):
        return []  # a rule on the keys of a mapping: the type error of the same value tells it
    if kind == "additionalProperties" and isinstance(instance, dict):
        known = error.schema.get("properties", {})
        names = ", ".join(known)
        if branch:
            return [Problem(key_path(parts + [key]), f"got {show(instance[key])}; not allowed {branch} "
                            f"(allowed keys: {names})") for key in instance if key not in known]
        return [Problem(key_path(parts + [key]), f"unknown key (value {show(instance[key])}); allowed keys "
                        f"here: {names}") for key in instance if key not in known]
    if kind in ("oneOf", "anyOf") and _keys_of_branches(error.validator_value):
        if not isinstance(instance, dict):
            return []  # a rule on the keys of a mapping: the type error of the same value tells it
        keys = _keys_of_branches(error.validator_value)
        given = [key for key in keys if key in instance]
        count = "exactly one" if kind == "oneOf" else "at least one"
        return [Problem(key_path(parts), f"got {'the keys ' + ', '.join(given) if given else 'none of them'}; "
                        f"allowed: {count} of the keys {', '.join(keys)}")]
    if kind == "minProperties" and isinstance(instance, dict):
        least, cases = error.validator_value, parts[-1:] == ["cases"]
        what = (f"one {'case' if cases else 'entry'}" if least == 1
                else f"{least} {'cases' if cases else 'entries'}")
        return [Problem(key_path(parts), f"got {len(instance) or 'no'} entries; allowed: at least {what} -- "
                        f"{allowed(parts, schema, root)}")]
    if kind == "uniqueItems":
        return [Problem(key_path(parts), f"got {show(instance)}; allowed: distinct values")]
    got = f"got {show(instance)}"
    if kind == "type":
        got += f" ({type_name(instance)})"
    return [Problem(key_path(parts), f"{got}; allowed: {allowed(parts, schema, root)}")]


def _name_problem(parts: list, error: jsonschema.ValidationError) -> Problem:
    """The problem of a name that a mapping's ``propertyNames`` refuses (a pattern, or a list of
    names): the name is the value found."""
    name = error.instance
    noun = "case name" if parts[-1:] == ["cases"] else "name"
    why = ", as the name becomes a file name" if error.validator == "pattern" else ""
    return Problem(key_path(parts + [name]), f"illegal {noun} {name!r}; allowed: {_allowed_values(error.schema)}{why}")


def _keys_of_branches(branches: Any) -> list[str]:
    """The keys of branches that each only require keys (``oneOf: [{required: [gains]}, ...]``),
    [] for branches of another form."""
    if not isinstance(branches, list) or not all(isinstance(rule, dict) and set(rule) == {"required"}
                                                 for rule in branches):
        return []
    return [key for rule in branches for key in rule["required"]]


#: the patterns of the schema in words
_PATTERNS = {"^[A-Za-z0-9_-]+$": "letters, digits, '_' and '-' only",
             "^[A-Za-z0-9_]+$": "letters, digits and '_' only",
             "^[A-Za-z_][A-Za-z0-9_]*$": "a name of letters, digits and '_', not starting with a digit",
             "^[A-Za-z0-9_]+(\\.[A-Za-z0-9_]+)*$": "keys of letters, digits and '_' joined by '.' "
                                                 "(a dotted path such as maneuver.design.speed)",
             "^[A-Za-z][A-Za-z0-9_]*$": "a name of letters, digits and '_', starting with a letter",
             "^(beam|root_spring|damping|tip_mass|drive|sensors)\\.[A-Za-z0-9_.]+$":
                 "a configuration key under beam, root_spring, damping, tip_mass, drive or sensors "
                 "(such as root_spring.stiffness)"}


def _pattern_words(pattern: Any) -> str:
    """A pattern of the schema said in words (:data:`_PATTERNS`; a test keeps it complete)."""
    if not isinstance(pattern, str):
        return "text as described in docs/configuration.md"
    return _PATTERNS.get(pattern, f"text matching the pattern {pattern}")


def _branch_condition(error: jsonschema.ValidationError) -> str:
    """The condition of the branch ``error`` arose in: its ``title`` (the beam's forms), "when kind
    is 'torque'" in the branch of one kind, else ''."""
    if "then" not in error.absolute_schema_path:
        return ""
    if "title" in error.schema:
        return error.schema["title"]
    kind = error.instance.get("kind") if isinstance(error.instance, dict) else None
    return f"when kind is {kind!r}" if kind is not None else ""


def _schema_at(parts: list, schema: dict, root: Any = None) -> dict:
    """The schema of the value at ``parts`` ($refs resolved, sibling keys kept, the branches whose
    condition the value of ``root`` there meets merged in), {} if none."""
    node, value = _with_branches(_resolve(schema, schema), root, schema), root
    for part in parts:
        value = _child(value, part)
        if isinstance(part, int):
            node = node.get("items", {})
        elif part in node.get("properties", {}):
            node = node["properties"][part]
        elif isinstance(node.get("additionalProperties"), dict):
            node = node["additionalProperties"]
        else:
            return {}
        node = _with_branches(_resolve(node, schema), value, schema)
    return node


def _child(value: Any, part) -> Any:
    if isinstance(value, dict):
        return value.get(part)
    if isinstance(value, list) and isinstance(part, int) and 0 <= part < len(value):
        return value[part]
    return None


def _with_branches(node: dict, value: Any, schema: dict) -> dict:
    """``node`` with the ``then`` part of every ``allOf`` rule whose ``if`` ``value`` meets."""
    for rule in node.get("allOf", []):
        if "then" in rule and isinstance(value, dict) and Validator(rule["if"]).is_valid(value):
            then = _resolve(rule["then"], schema)
            node = {**node, **then, "properties": {**node.get("properties", {}), **then.get("properties", {})}}
    return node


def _resolve(node: dict, schema: dict) -> dict:
    if "$ref" not in node:
        return node
    target = schema
    for key in node["$ref"].removeprefix("#/").split("/"):
        target = target[key]
    return {**_resolve(target, schema), **{key: value for key, value in node.items() if key != "$ref"}}


def allowed(parts: list, schema: dict, root: Any = None) -> str:
    """What the schema allows at ``parts`` (in the instance ``root``, which selects the branches of
    kinds), followed by the key's description."""
    node = _schema_at(parts, schema, root)
    text = _allowed_values(node, schema)
    return f"{text} -- {node['description'].strip()}" if "description" in node else text


def _allowed_values(node: dict, schema: dict | None = None) -> str:
    """What ``node`` (its ``$ref`` resolved in ``schema``, default :data:`SCHEMA`) allows, in words."""
    node = _resolve(node, SCHEMA if schema is None else schema) if isinstance(node, dict) else {}
    if "enum" in node:
        return "one of " + ", ".join(map(str, node["enum"]))
    if "const" in node:
        return f"only {node['const']}"
    kind = node.get("type")
    if kind in ("number", "integer"):
        bounds = [f"{symbol} {node[key]}" for key, symbol in
                  (("minimum", ">="), ("exclusiveMinimum", ">"), ("maximum", "<="), ("exclusiveMaximum", "<"))
                  if key in node]
        return ("an integer" if kind == "integer" else "a number") + (" " + " and ".join(bounds) if bounds else "")
    if kind == "array":
        distinct = " distinct" if node.get("uniqueItems") else ""
        size = (f"{node['minItems']}" if node.get("maxItems") == node.get("minItems", 0)
                else f"at least {node.get('minItems', 0)}" + (f" and at most {node['maxItems']}" if "maxItems" in node
                                                              else ""))
        each = f", each {_allowed_values(node['items'], schema)}" if "items" in node else ""
        return f"a list of {size}{distinct} values{each}"
    if kind == "object" and "enum" in node.get("properties", {}).get("kind", {}) and "allOf" in node:
        return f"a mapping with a kind ({', '.join(node['properties']['kind']['enum'])}) and the keys of its kind"
    if kind == "object" and "properties" in node:
        return "a mapping with keys " + ", ".join(node["properties"])
    if kind == "object":
        return "a mapping"
    if kind == "string" or (kind is None and "pattern" in node):
        text = _pattern_words(node["pattern"]) if "pattern" in node else "text"
        return f"{text}, not empty" if node.get("minLength", 0) > 0 and "pattern" not in node else text
    if kind == "boolean":
        return "true or false"
    return "a value as described in docs/configuration.md"


def show(value: Any) -> str:
    if isinstance(value, (dict, list)) or value is None:
        text = json.dumps(value, default=str)
        return text if len(text) <= 80 else text[:77] + "..."
    return repr(value)


def type_name(value: Any) -> str:
    return _TYPE_NAMES.get(type(value), type(value).__name__)


def key_path(parts: list) -> str:
    path = ""
    for part in parts:
        path += f"[{part}]" if isinstance(part, int) and not isinstance(part, bool) else f".{part}"
    return path.lstrip(".") or "<top level>"
