"""docs/configuration.md is generated from the config schema: the committed file is current, every
key is documented, and the generator resolves references and conditions as JSON Schema means them."""

from __future__ import annotations

import pytest

from hubbeam.configuration import reference as config_reference
from hubbeam.configuration.reference import MARKER, REGENERATE, reference, render, resolve
from hubbeam.configuration.schema import SCHEMA


def _properties(node: dict, defs: dict, path: str = ""):
    """Yield (dotted key, resolved schema) of every property, map entries as ``<name>``."""
    node = resolve(node, defs)
    for name, sub in node.get("properties", {}).items():
        key = f"{path}.{name}" if path else name
        yield key, resolve(sub, defs)
        yield from _properties(sub, defs, key)
    if isinstance(node.get("additionalProperties"), dict):
        yield from _properties(node["additionalProperties"], defs, f"{path}.<name>")
    if isinstance(node.get("items"), dict):
        yield from _properties(node["items"], defs, f"{path}[]")


def test_committed_reference_is_current():
    committed = config_reference.DOC_PATH.read_text(encoding="utf-8")
    assert committed == render(), f"docs/configuration.md is stale; regenerate it with {REGENERATE}"


def test_every_schema_property_has_a_description():
    keys = list(_properties(SCHEMA, SCHEMA["$defs"]))
    assert len(keys) > 50  # the walk reaches the nested sections and the map entries
    missing = [key for key, node in keys if not str(node.get("description", "")).strip()]
    assert not missing, f"schema properties without a description: {missing}"


def _sections(markdown: str) -> dict[str, set[str]]:
    """The keys of the table rows under each heading of ``markdown``, by heading text."""
    sections: dict[str, set[str]] = {"": set()}
    title = ""
    for line in markdown.splitlines():
        if line.startswith("#"):
            title = line.lstrip("#").strip().strip("`")
            sections[title] = set()
        elif line.startswith("| `"):
            sections[title].add(line.split("`")[1])
    return sections


def _node_at(title: str) -> dict:
    """The schema mapping a section title names: a dotted path from the top level or from a $def,
    or the branch of one kind of such a mapping ("maneuver` when `kind` is `torque"), and a
    mapping inside such a branch ("maneuver` when `kind` is `state_feedback.design")."""
    defs = SCHEMA["$defs"]
    if "` when `" in title:
        path, condition = title.split("` when `")
        key, value = condition.split("` is `")
        value, *inside = value.split(".")
        (then,) = [rule["then"] for rule in _node_at(path)["allOf"]
                   if rule["if"]["properties"][key]["const"] == value]
        node = resolve(then, defs)
        return _inside(node, inside)
    first, *rest = title.split(".")
    return _inside(resolve(SCHEMA["properties"][first] if first in SCHEMA["properties"] else defs[first],
                           defs), rest)


def _inside(node: dict, parts) -> dict:
    """The mapping at the dotted ``parts`` below ``node`` (``<name>``: any key's mapping)."""
    for part in parts:
        child = node["additionalProperties"] if part == "<name>" else node["properties"][part]
        node = resolve(child, SCHEMA["$defs"])
    return node


def test_every_section_lists_exactly_the_keys_of_its_mapping():
    sections = _sections(reference())
    assert sections.pop("") == set(SCHEMA["properties"])
    sections.pop("Shared definitions")
    assert {"beam", "numerics.convergence_check", "case", "maneuver", "sweep.figure",
            "maneuver` when `kind` is `pd", "damping` when `kind` is `modal"} <= set(sections)
    for title, keys in sections.items():
        assert keys == set(_node_at(title).get("properties", {})), title


def test_every_mapping_of_the_schema_has_a_section():
    sections = list(_sections(reference()).values())
    mappings = [(key, node) for key, node in _properties(SCHEMA, SCHEMA["$defs"])]
    mappings += [(f"$defs.{name}", resolve(node, SCHEMA["$defs"])) for name, node in SCHEMA["$defs"].items()]
    for key, node in mappings:
        if node.get("properties"):
            assert set(node["properties"]) in sections, f"no section lists the keys of {key}"


SMALL = {
    "type": "object",
    "required": ["run"],
    "properties": {
        "run": {"$ref": "#/$defs/motion", "description": "How it runs.",
                "properties": {"kind": {"const": "spin", "description": "spin only."}}},
        "grid": {"$ref": "#/$defs/range", "description": "Values swept."},
        "count": {"$ref": "#/$defs/count", "description": "How many."},
    },
    "$defs": {
        "count": {"type": "integer", "minimum": 1, "maximum": 20},
        "range": {"type": "object", "required": ["start"],
                  "properties": {"start": {"type": "number", "exclusiveMinimum": 0, "default": 1.0,
                                           "description": "First value."}}},
        "motion": {
            "type": "object", "required": ["kind"],
            "properties": {"kind": {"enum": ["spin", "push"], "description": "Kind."},
                           "speed": {"type": "number", "description": "Speed."},
                           "force": {"type": "number", "description": "Force."}},
            "allOf": [{"if": {"properties": {"kind": {"const": "spin"}}, "required": ["kind"]},
                       "then": {"required": ["speed"], "not": {"required": ["force"]}}},
                      {"if": {"properties": {"kind": {"const": "push"}}, "required": ["kind"]},
                       "then": {"required": ["force", "speed"]}}],
        },
    },
}


def test_reference_with_siblings_is_merged_in_place():
    text = reference(SMALL)
    assert "\n## `run`\n" in text  # a section of its own: the $ref carries extra keywords
    assert "| `kind` | text | yes | - | only `spin` | spin only. |" in text


def test_whole_mapping_definition_is_linked_once_and_scalar_definition_inlined():
    text = reference(SMALL)
    assert "| `grid` | mapping | no | - | see [`range`](#range) | Values swept. |" in text
    assert text.count("### `range`") == 1
    assert "| `start` | number | yes | `1.0` | > 0 | First value. |" in text
    assert "| `count` | integer | no | - | >= 1; <= 20 | How many. |" in text


def test_conditions_become_required_and_forbidden_cells():
    text = reference(SMALL)
    assert "| `speed` | number | when `kind` is `spin` or `push` | - | any | Speed. |" in text
    assert "| `force` | number | when `kind` is `push` | - | not allowed when `kind` is `spin` | Force. |" in text


def test_unsupported_reference_is_an_error_naming_it():
    with pytest.raises(ValueError, match="elsewhere.yaml"):
        reference({"type": "object", "properties": {"x": {"$ref": "elsewhere.yaml"}}})


def test_template_needs_the_marker_once():
    assert render(SMALL, f"# Title\n\n{MARKER}\n").startswith("<!-- Generated by")
    with pytest.raises(ValueError, match="marker"):
        render(SMALL, "# Title without the marker\n")


def test_check_fails_on_a_stale_file_and_says_how_to_regenerate(tmp_path, monkeypatch, capsys):
    doc = tmp_path / "configuration.md"
    monkeypatch.setattr(config_reference, "DOC_PATH", doc)
    doc.write_text("outdated\n", encoding="utf-8")
    assert config_reference.main(["--check"]) == 1
    assert REGENERATE in capsys.readouterr().err
    assert config_reference.main([]) == 0
    assert config_reference.main(["--check"]) == 0


def test_placeholders_in_descriptions_survive_markdown():
    schema = {"type": "object", "description": "Each run becomes `runs/<name>.nc` and figures/<name>.pdf, <= 3.",
              "properties": {}}
    assert "Each run becomes `runs/<name>.nc` and figures/&lt;name>.pdf, <= 3." in reference(schema)
