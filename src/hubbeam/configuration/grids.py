"""Cases generated from a grid (``case_grids``): one base case, the keys that vary over it, a name per case.

A study of many similar cases states them once::

    case_grids:
      trust:
        name: "{design}_on_{model}_w{speed}"
        case: {model: CFOAM, t_end: 30.0, maneuver: {...}}        # the base case
        axes:
          - design: {keys: [maneuver.design.model], values: [TLAM, TLAM, SFOAM, SFOAM, FOAM, FOAM]}
            model: {keys: [model], values: [CFOAM, TLAM, CFOAM, SFOAM, CFOAM, FOAM]}
          - speed: {keys: [maneuver.reference.wf, maneuver.design.speed], values: [1.0, 1.5, 2.0]}

Within an axis the entries vary together (their ``values`` have one length); the axes combine in
every way (their product, in the order given). An entry sets each of its ``keys`` (dotted paths
into the case, created where missing) to its value; the case's name is ``name`` with each entry's
value in place of ``{entry}``: text in lower case, a number written shortest (``%g``) with ``p``
for the decimal point and ``m`` for a minus (1.5 -> ``1p5``, -2 -> ``m2``).
:func:`expand_case_grids` adds the cases to ``cases`` before the configuration is checked, so every
generated case is checked as a written one is; a name that clashes with another case is refused,
unless that case is the same (a configuration that records its expanded cases, such as the
archive's ``config.used.yaml``, expands to itself).
"""

from __future__ import annotations

import copy
import itertools
import string
from collections.abc import Mapping
from typing import Any

from hubbeam.configuration.schema import SCHEMA, Problem, Validator


def name_token(value: Any) -> str:
    """``value`` as a part of a case name (module docstring)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value).lower()
    return f"{value:g}".replace("-", "m").replace(".", "p").replace("+", "")


def _set(case: dict, path: str, value: Any) -> None:
    *parents, last = path.split(".")
    node = case
    for key in parents:
        node = node.setdefault(key, {})
        if not isinstance(node, dict):
            raise KeyError(key)
    node[last] = copy.deepcopy(value)


#: a validator of the ``case_grids`` section alone
GRIDS_VALIDATOR = Validator({**SCHEMA["properties"]["case_grids"], "$defs": SCHEMA["$defs"]})


def _grid_problems(where: str, grid: Mapping) -> list[Problem]:
    """An axis's entries have values of one length; the name template uses exactly the entries."""
    problems = []
    entries = []
    for a, axis in enumerate(grid["axes"]):
        lengths = {name: len(entry["values"]) for name, entry in axis.items()}
        if len(set(lengths.values())) > 1:
            problems.append(Problem(f"{where}.axes[{a}]", f"entries of {lengths} values; allowed: one length "
                                    "in an axis (its entries vary together)"))
        entries += list(axis)
    fields = {field for _, field, _, _ in string.Formatter().parse(grid["name"]) if field is not None}
    if fields != set(entries) or len(entries) != len(set(entries)):
        problems.append(Problem(f"{where}.name", f"got {grid['name']!r} with the fields {sorted(fields)}; allowed: "
                                f"a template with each entry of the axes once as {{entry}} ({', '.join(entries)}), "
                                "so that every case gets a name of its own"))
    return problems


def grid_cases(grid: Mapping) -> dict[str, dict]:
    """The cases of one checked grid, by name (module docstring)."""
    cases = {}
    axes = [[dict(zip(axis, values)) for values in zip(*(entry["values"] for entry in axis.values()))]
            for axis in grid["axes"]]
    for combination in itertools.product(*axes):
        chosen = {name: value for row in combination for name, value in row.items()}
        case = copy.deepcopy(grid["case"])
        for axis in grid["axes"]:
            for name, entry in axis.items():
                for path in entry["keys"]:
                    _set(case, path, chosen[name])
        cases[grid["name"].format(**{name: name_token(value) for name, value in chosen.items()})] = case
    return cases


def expand_case_grids(cfg: dict) -> list[Problem]:
    """Add the cases of every grid of ``cfg["case_grids"]`` to ``cfg["cases"]`` (in place; module
    docstring); return the problems that stop it (the section's shape, an axis of unequal entries,
    a name template, a name clash, a key path through a value that is no mapping)."""
    grids = cfg.get("case_grids")
    if grids is None or not GRIDS_VALIDATOR.is_valid(grids):
        return []  # the schema reports the section
    cases = cfg.setdefault("cases", {})
    if not isinstance(cases, dict):
        return []  # the schema reports it
    problems = []
    for name, grid in grids.items():
        where = f"case_grids.{name}"
        found = _grid_problems(where, grid)
        if found:
            problems += found
            continue
        try:
            generated = grid_cases(grid)
        except KeyError as error:
            problems.append(Problem(f"{where}.axes", f"a key path runs through {error.args[0]!r}, which the base "
                                    "case holds as a value, not a mapping; allowed: paths into the case's mappings"))
            continue
        for case_name, case in generated.items():
            if case_name in cases and cases[case_name] != case:
                problems.append(Problem(f"{where}.name", f"generates {case_name!r}, a case given apart; allowed: "
                                        "names of their own"))
            else:
                cases[case_name] = case
    return problems
