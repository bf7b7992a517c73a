"""The configuration reference ``docs/configuration.md``, generated from the config schema.

Every key of the schema ``src/hubbeam/configuration/schemas/config.schema.yaml`` is listed with its type, whether it is
required, its default, what is allowed and its description, all taken from the schema alone.
The hand-written prose around the reference (where the configuration lives, how YAML numbers
are written, an example) is the template ``docs/templates/configuration.md``; the generated
reference replaces its marker line.

    python -m hubbeam.configuration.reference           # (re)write docs/configuration.md
    python -m hubbeam.configuration.reference --check   # exit 1 when docs/configuration.md is stale

Shared definitions (``$defs``) referenced as whole mappings are described once, in their own
section, and linked from every key that uses them; a reference with extra keywords beside it, or
to a scalar definition, is resolved in place.
"""

from __future__ import annotations

import argparse
import copy
import json
import re
import sys
from collections.abc import Mapping
from pathlib import Path

from hubbeam.configuration.schema import SCHEMA
from hubbeam.reporting.document import markdown_table

#: the source tree (the reference is written there, by a developer)
ROOT = Path(__file__).resolve().parents[3]
SCHEMA_PATH = ROOT / "src" / "hubbeam" / "configuration" / "schemas" / "config.schema.yaml"
TEMPLATE_PATH = ROOT / "docs" / "templates" / "configuration.md"
DOC_PATH = ROOT / "docs" / "configuration.md"
MARKER = "<!-- reference -->"
#: heading level of the reference's sections: below the template's "## Reference"
REFERENCE_LEVEL = 3
REGENERATE = "python -m hubbeam.configuration.reference"

_TYPE_NAMES = {"number": "number", "integer": "integer", "string": "text", "boolean": "boolean",
               "object": "mapping", "array": "list"}
_TAG_START = re.compile(r"<(?=[A-Za-z/!?])")
_BOUNDS = (("minimum", ">="), ("exclusiveMinimum", ">"), ("maximum", "<="), ("exclusiveMaximum", "<"))


def _ref_name(ref: str) -> str:
    prefix = "#/$defs/"
    if not ref.startswith(prefix):
        raise ValueError(f"config schema: $ref {ref!r} is not supported; allowed: '{prefix}<name>'")
    return ref[len(prefix):]


def _overlay(base: dict, extra: Mapping) -> dict:
    """``base`` with the keywords of ``extra`` on top; ``properties`` are merged per property."""
    merged = copy.deepcopy(base)
    for key, value in extra.items():
        if key == "properties":
            properties = merged.setdefault("properties", {})
            for name, sub in value.items():
                properties[name] = _overlay(properties.get(name, {}), sub)
        else:
            merged[key] = copy.deepcopy(value)
    return merged


def resolve(node: Mapping, defs: Mapping) -> dict:
    """``node`` with its own ``$ref`` replaced by the definition, sibling keywords on top."""
    if "$ref" not in node:
        return dict(node)
    siblings = {key: value for key, value in node.items() if key != "$ref"}
    return _overlay(resolve(defs[_ref_name(node["$ref"])], defs), siblings)


def _linked_definition(node: Mapping, defs: Mapping) -> str | None:
    """The ``$defs`` name when ``node`` is a whole mapping definition described in its own section."""
    if "$ref" not in node or set(node) - {"$ref", "description"}:
        return None
    name = _ref_name(node["$ref"])
    return name if resolve(defs[name], defs).get("type") == "object" else None


def _value(value) -> str:
    return f"`{json.dumps(value)}`" if not isinstance(value, str) else f"`{value}`"


def _text(text: str) -> str:
    """One line of Markdown: whitespace collapsed; a '<' that would open an HTML tag (as in
    ``<name>``) is escaped outside code spans."""
    parts = " ".join(text.split()).split("`")
    return "`".join(part if index % 2 else _TAG_START.sub("&lt;", part) for index, part in enumerate(parts))


def _bounds(node: Mapping) -> list[str]:
    return [f"{sign} {node[key]:g}" for key, sign in _BOUNDS if key in node]


def _type(node: Mapping, defs: Mapping) -> str:
    if "enum" in node or "const" in node:
        return "text" if all(isinstance(v, str) for v in node.get("enum", [node.get("const")])) else "value"
    kind = _TYPE_NAMES.get(node.get("type"), "value")
    if node.get("type") == "array":
        kind += " of " + _type(resolve(node.get("items", {}), defs), defs)
    return kind


def _allowed(node: Mapping, defs: Mapping) -> list[str]:
    """What the schema allows for one value (bounds, names, list and mapping sizes)."""
    allowed = _bounds(node)
    if "const" in node:  # a const narrows an enum beside it
        allowed.append("only " + _value(node["const"]))
    elif "enum" in node:
        allowed.append("one of " + ", ".join(_value(v) for v in node["enum"]))
    if "pattern" in node:
        allowed.append(f"matching `{node['pattern']}`")
    if "minItems" in node:
        allowed.append(f"at least {node['minItems']} item{'s' if node['minItems'] > 1 else ''}")
    if "maxItems" in node:
        allowed.append(f"at most {node['maxItems']} items")
    if node.get("uniqueItems"):
        allowed.append("distinct")
    if "items" in node:
        items = _allowed(resolve(node["items"], defs), defs)
        if items:
            allowed.append("each " + ", ".join(items))
    if "minProperties" in node and node["minProperties"] == node.get("maxProperties"):
        allowed.append(f"exactly {node['minProperties']} keys")
    else:
        if "minProperties" in node:
            allowed.append(f"at least {node['minProperties']} key{'s' if node['minProperties'] > 1 else ''}")
        if "maxProperties" in node:
            allowed.append(f"at most {node['maxProperties']} keys")
    return allowed


def _condition(rule: Mapping) -> tuple[tuple[str | None, object], dict]:
    """One ``if``/``then`` rule of ``allOf`` as ((key, value) tested, then-part); a then-part with a
    ``title`` (a form of the beam) as ((None, title), then-part)."""
    tests = rule["if"].get("properties", {})
    if set(rule) == {"if", "then"} and "title" in rule["then"]:
        return (None, rule["then"]["title"]), rule["then"]
    if set(rule) != {"if", "then"} or len(tests) != 1 or "const" not in next(iter(tests.values())):
        raise ValueError(f"config schema: conditional {rule!r} is not supported; allowed: "
                         "if: {properties: {<key>: {const: <value>}}} with a then: part, or a then: part "
                         "with a title")
    (key, test), = tests.items()
    return (key, test["const"]), rule["then"]


def _forbidden(then: Mapping) -> list[str]:
    """Keys a ``then`` part forbids: ``not: {required: [...]}`` or ``not: {anyOf: [{required}...]}``."""
    negated = then.get("not", {})
    alternatives = negated.get("anyOf", [negated] if negated else [])
    return [key for alternative in alternatives for key in alternative.get("required", [])]


def _when(conditions: list[tuple[str | None, object]]) -> str:
    """'when `kind` is `a` or `b`' for conditions on one key (several keys joined by 'or'); the
    titles of forms as they are."""
    values: dict[str, list] = {}
    for key, value in conditions:
        if key is not None:
            values.setdefault(key, []).append(_value(value))
    titles = [value for key, value in conditions if key is None]
    kinds = ["when " + " or ".join(f"`{key}` is {' or '.join(vals)}" for key, vals in values.items())] if values else []
    return " or ".join(kinds + titles)


def _conditional(node: Mapping) -> tuple[dict, dict]:
    """Per property: the conditions under which it is required, and those under which it is forbidden."""
    required: dict[str, list] = {}
    forbidden: dict[str, list] = {}
    for rule in node.get("allOf", []):
        condition, then = _condition(rule)
        for key in then.get("required", []) if "$ref" not in then else ():
            required.setdefault(key, []).append(condition)
        for key in _forbidden(then):
            forbidden.setdefault(key, []).append(condition)
    return required, forbidden


def _join(parent: str, name: str) -> str:
    return f"{parent}.{name}" if parent else name


def _anchor(title: str) -> str:
    """The anchor GitHub gives a heading (lower case, punctuation but '-' and '_' dropped)."""
    kept = "".join(c for c in title.lower() if c.isalnum() or c in " -_")
    return kept.replace(" ", "-")


class _Writer:
    """Walks the schema depth first, one section per mapping."""

    def __init__(self, schema: Mapping):
        self.defs = schema.get("$defs", {})
        self.lines: list[str] = []
        self.linked: list[str] = []

    def section(self, title: str, node: Mapping, level: int) -> None:
        node = resolve(node, self.defs)
        self.lines += [f"{'#' * level} `{title}`", ""]
        if node.get("description"):
            self.lines += [_text(node["description"]), ""]
        entries = node.get("additionalProperties")
        if isinstance(entries, Mapping):
            self.map_entries(title, node, entries, level)
            return
        self.table(title, node)
        for name, sub in node.get("properties", {}).items():
            if _linked_definition(sub, self.defs) is None and resolve(sub, self.defs).get("type") == "object":
                self.section(f"{title}.{name}", sub, min(level + 1, 6))
        for rule in node.get("allOf", []):  # the keys of each kind, a branch of their own
            (key, value), then = _condition(rule)
            only = node.get("properties", {}).get(key, {}).get("const", value)  # a kind narrowed to one
            if "$ref" in then and only == value:
                selector = {"properties": {key: {"description": f"{value}: the keys of this section"}}}
                self.section(f"{title}` when `{key}` is `{value}", _overlay(resolve(then, self.defs), selector),
                             min(level + 1, 6))

    def map_entries(self, title: str, node: Mapping, entries: Mapping, level: int) -> None:
        rules = _allowed(node.get("propertyNames", {}), self.defs) + _allowed(node, self.defs)
        names = f"Keys are names ({', '.join(rules)})" if rules else "Keys are names"
        linked = _linked_definition(entries, self.defs)
        if linked:
            self.lines += [f"{names}; each entry is a [`{linked}`](#{_anchor(linked)}) mapping.", ""]
            self.link(linked)
        else:
            self.lines += [f"{names}; each entry is described in `{title}.<name>`.", ""]
            self.section(f"{title}.<name>", entries, min(level + 1, 6))

    def link(self, name: str) -> None:
        if name not in self.linked:
            self.linked.append(name)

    def table(self, title: str, node: Mapping) -> None:
        properties = node.get("properties", {})
        if not properties:
            return
        required = set(node.get("required", []))
        when_required, when_forbidden = _conditional(node)
        rows = []
        for name, raw in properties.items():
            sub = resolve(raw, self.defs)
            allowed = _allowed(sub, self.defs)
            if name in when_forbidden:
                allowed.append("not allowed " + _when(when_forbidden[name]))
            linked = _linked_definition(raw, self.defs)
            items = _linked_definition(sub["items"], self.defs) if isinstance(sub.get("items"), Mapping) else None
            if linked:
                self.link(linked)
                allowed.insert(0, f"see [`{linked}`](#{_anchor(linked)})")
            elif items:
                self.link(items)
                allowed.insert(0, f"each a [`{items}`](#{_anchor(items)}) mapping")
            elif sub.get("type") == "object":
                allowed.insert(0, f"see `{_join(title, name)}`")
            if name in required:
                needed = "yes"
            elif name in when_required:
                needed = _when(when_required[name])
            else:
                needed = "no"
            default = _value(sub["default"]) if "default" in sub else "-"
            rows.append([_text(text) for text in (f"`{name}`", _type(sub, self.defs), needed, default,
                                                  "; ".join(allowed) or "any", sub.get("description", ""))])
        self.lines += markdown_table(("key", "type", "required", "default", "allowed", "description"),
                                     rows).splitlines() + [""]

    def definitions(self, level: int) -> None:
        """The linked ``$defs`` sections, including the ones they link in turn."""
        if not self.linked:
            return
        self.lines += [f"{'#' * level} Shared definitions", "",
                       "Mappings the schema defines once, linked from the keys that use them.", ""]
        done = 0
        while done < len(self.linked):
            name = self.linked[done]
            self.section(name, self.defs[name], min(level + 1, 6))
            done += 1


def reference(schema: Mapping = SCHEMA, level: int = 2) -> str:
    """The Markdown reference of every configuration key of ``schema``, headings from ``level``."""
    writer = _Writer(schema)
    if schema.get("description"):
        writer.lines += [_text(schema["description"]), ""]
    writer.table("", schema)
    for name, node in schema.get("properties", {}).items():
        writer.section(name, node, level)
    writer.definitions(level)
    return "\n".join(writer.lines).rstrip("\n") + "\n"


def render(schema: Mapping = SCHEMA, template: str | None = None) -> str:
    """``docs/configuration.md``: the hand-written template with the reference at its marker."""
    template = TEMPLATE_PATH.read_text(encoding="utf-8") if template is None else template
    if template.count(MARKER) != 1:
        raise ValueError(f"{TEMPLATE_PATH}: needs the marker line {MARKER!r} exactly once, "
                         f"found {template.count(MARKER)}")
    header = (f"<!-- Generated by `{REGENERATE}` from {SCHEMA_PATH.relative_to(ROOT).as_posix()} and "
              f"{TEMPLATE_PATH.relative_to(ROOT).as_posix()}; edit those, not this file. -->\n\n")
    return header + template.replace(MARKER, reference(schema, REFERENCE_LEVEL).rstrip("\n"))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog=REGENERATE, description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="do not write; exit 1 when docs/configuration.md differs from the schema")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        current = DOC_PATH.read_text(encoding="utf-8") if DOC_PATH.is_file() else ""
        if current != text:
            print(f"{DOC_PATH} is stale (the schema or the template changed); "
                  f"regenerate it with: {REGENERATE}", file=sys.stderr)
            return 1
        print(f"{DOC_PATH} is up to date")
        return 0
    DOC_PATH.write_text(text, encoding="utf-8")
    print(f"wrote {DOC_PATH}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
