"""The configuration schema and how its violations are told to the user.

The package data ``hubbeam/schemas/config.schema.yaml`` (JSON schema, draft 2020-12; found through
:mod:`importlib.resources`, so an installed package checks configurations too) describes the shape, types,
ranges and allowed names of a configuration. The bounds of :mod:`hubbeam.limits` are filled into it
when it is read (:data:`SCHEMA_LIMITS`), so the file states none of them. :func:`explain` turns one
schema error into :class:`Problem` entries that name the key path, the value found and what is
allowed; :func:`coerce_numbers` takes text that reads as a finite number for a number where the
schema wants one (YAML 1.1 reads ``1e-9`` as text).
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

from hubbeam import limits

#: the schema, package data of hubbeam
SCHEMA_RESOURCE = resources.files("hubbeam") / "schemas" / "config.schema.yaml"


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


#: schema node (keys from the root) -> the bounds of :mod:`hubbeam.limits` filled in at load time;
#: the schema file states none of these numbers itself
SCHEMA_LIMITS = {
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


#: Case names double as wildcards and file names (``results/simulations/<case>.nc``).
CASE_NAME_PATTERN = SCHEMA["properties"]["cases"]["propertyNames"]["pattern"].strip("^$")


# "integer" means a YAML integer: 5.0 is rejected rather than silently used as an array size.
Validator = jsonschema.validators.extend(
    jsonschema.Draft202012Validator,
    type_checker=jsonschema.Draft202012Validator.TYPE_CHECKER.redefine(
        "integer", lambda _checker, value: isinstance(value, int) and not isinstance(value, bool)
    ),
)


def coerce_numbers(node: Any, schema: dict, parts: list | None = None) -> None:
    """Replace, in place, every text in ``node`` that stands where ``schema`` wants a number and
    reads as a finite decimal number (``"1e-9"``, ``"2.7667e3"``, ``"2.0"``) by that number.

    YAML 1.1, the rules Snakemake reads configs with, takes an exponent form without a decimal
    point or without a signed exponent for text; converting it here, before validation, lets the
    rules receive floats. Other text (``"fast"``, ``"nan"``) stays and the schema rejects it.
    """
    parts = [] if parts is None else parts
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in list(items):
        where = parts + [key]
        if isinstance(value, (dict, list)):
            coerce_numbers(value, schema, where)
        elif isinstance(value, str) and _schema_at(where, schema).get("type") == "number":
            number = _finite_float(value)
            if number is not None:
                node[key] = number


def _finite_float(text: str) -> float | None:
    """``text`` as a finite float, None if it is not one."""
    try:
        number = float(text)
    except ValueError:
        return None
    return number if math.isfinite(number) else None


def explain(error: jsonschema.ValidationError, schema: dict) -> list[Problem]:
    """Turn one schema error into problems that name key, value and what is allowed."""
    parts = list(error.absolute_path)
    kind, instance = error.validator, error.instance
    if "propertyNames" in error.absolute_schema_path:
        return [Problem(key_path(parts + [instance]),
                        f"illegal case name {instance!r}; allowed: letters, digits, '_' and '-' "
                        f"(pattern {CASE_NAME_PATTERN}), as the name becomes a file name")]
    if kind == "required":
        why = f"required when kind is {instance.get('kind')!r}" if "then" in error.absolute_schema_path else "required"
        return [Problem(key_path(parts + [key]), f"missing ({why}); allowed: {allowed(parts + [key], schema)}")
                for key in error.validator_value if key not in instance]
    if kind == "not":  # a maneuver key that belongs to the other kind
        allowed_keys = ", ".join(["kind", *error.schema["required"]])
        return [Problem(key_path(parts + [key]), f"got {show(instance[key])}; not allowed when kind is "
                        f"{instance['kind']!r} (allowed keys: {allowed_keys})")
                for key in error.validator_value["required"]]
    if kind == "additionalProperties":
        known = error.schema.get("properties", {})
        return [Problem(key_path(parts + [key]), f"unknown key (value {show(instance[key])}); allowed keys "
                        f"here: {', '.join(known)}") for key in instance if key not in known]
    if kind == "minProperties":
        return [Problem(key_path(parts), "got no entries; allowed: at least one case")]
    if kind == "uniqueItems":
        return [Problem(key_path(parts), f"got {show(instance)}; allowed: distinct values")]
    got = f"got {show(instance)}"
    if kind == "type":
        got += f" ({type_name(instance)})"
    return [Problem(key_path(parts), f"{got}; allowed: {allowed(parts, schema)}")]





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


def allowed(parts: list, schema: dict) -> str:
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
