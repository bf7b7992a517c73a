"""Every key of every shipped configuration, mutated every way, is refused by name or accepted, never a crash.

For ``config/config.yaml`` and every ``studies/*.yaml``, every node of the YAML as written (each
leaf, each mapping and each list, in every section: cases, case_grids, control, validation,
sweeps, readings...; a YAML alias counts at each place it appears) is replaced, one at a time, by
each of :func:`mutations`: a wrong type (text for a number, a number for text), a list for a
scalar, a mapping or a scalar for a list, a scalar or a list for a mapping, a negative and a huge
number where a number is, NaN, a mapping with an unknown key added, and the empty values None,
``""``, ``[]`` and ``{}``. The one check of the workflow,
:func:`hubbeam.check.check_configuration`, runs on each mutant (with the configuration's
own file, which locates its ``file:`` tables).

The rule: the check returns no problem (the mutant is a valid configuration), or problems that
each name the mutated key ``P`` (:func:`attributed`):

* the problem's key path is ``P``, a key below it (``P.kind`` missing from a mapping emptied at
  ``P``) or a mapping above it (``cases.<name>`` or ``P``'s parent for a rule on the keys of a
  mapping, such as "exactly one of gains, output_feedback, design");
* or its text names ``P`` (``cases.a.t_end: ... allowed: t_end >= numerics.output_step = ...``
  when ``P`` is ``numerics.output_step``);
* a key of a case grid (``case_grids.<grid>``) is checked in the cases it generates: a problem
  of ``cases.<generated>.<rest>`` (or one whose text names it) names ``case_grids.<grid>.case.<rest>``,
  and a problem of a generated case or below it names the grid's other keys (its axes and name
  template set that case's values and name);
* a mutated ``cases`` or ``case_grids``, one of their entries, or a grid's name template or axes
  supplies the names of cases: a problem of ``cases`` (missing, or empty) or of a section that
  names cases (``study.comparisons``, ``control``) is the mutation's too, as the mutation took those
  cases away;
* a key of a grid's base case that an axis's key path runs through: the grid's problem at
  ``case_grids.<grid>.axes`` naming that key (``a key path runs through 'maneuver'``).

Anything else (a problem of an unrelated key, or any exception) fails, with the file, the key, the
mutation and the traceback.

Speed (14,085 mutants of 1,722 keys; the suite runs this, so it must take seconds): each
mutant is checked on the configuration reduced to the part the mutated key belongs to
(:func:`reduced`), itself checked to be valid first:

* a key of an entry of a collection (``cases.<name>``, ``case_grids.<grid>``, ``readings.<name>``,
  ``sweeps.maps.<name>``, ``validation.cases.<name>``) keeps that entry and drops the entries of
  every other collection (the first case stays when ``cases`` would be empty, and the validation
  case ``validation.convergence.case`` names stays with the validation section);
* a key of a collection's section outside its entries (``validation.published``,
  ``sweeps.numerics``, ``cases`` itself, ...) keeps one entry of each shape (the same keys with
  values of the same types) of that collection, and drops the entries of the others;
* any other key (``beam``, ``numerics``, ``eigen``, ``linear``, ``study``, ``products``,
  ``control``) keeps one entry of each shape of every collection;
* the lists of case names (``study.comparisons``, ``control``) keep the names left, but a list that
  holds the mutated key or lies below it keeps its cases;
* a grid generates its first case only (its axes cut to their first values), unless the key lies
  in one of its axes (the other axes cut), in the grid itself or its list of axes, or the grid
  generates a case a kept list names.

The checks of an entry read the sections outside the collections and the entries named through
those lists only, and the cases of a grid differ only in the values of its axes, so a reduced
mutant meets the checks a full one would. The matrices of a case and what a case resolves (its LQR
design, its sampled controller, its shaper) are deterministic in the case, the beam and the
numerics: they are computed once per distinct triple (:func:`memoised_checks`), and the YAML files
the check rereads for repeated keys are read once. So the whole takes about 35 s of one core; the
three configurations with the most keys (:data:`LARGEST`, about 25 s) are ``slow``
(tests/conftest.py), out of ``make test-fast``.

"""

from __future__ import annotations

import contextlib
import functools
import math
import traceback
from collections.abc import Iterator
from pathlib import Path
from typing import Any, NamedTuple

import pytest
from checking import checked_configuration

import hubbeam.configuration.load as load
import hubbeam.control.cases as control_cases
from hubbeam.configuration.grids import GRIDS_VALIDATOR, grid_cases
from hubbeam.configuration.load import read_config_file
from hubbeam.configuration.schema import key_path
from hubbeam.reporting.products import PAPER, PAPER_PRODUCTS, product_cases

REPO = Path(__file__).resolve().parents[1]
CONFIG_FILES = ["config/config.yaml", *sorted(str(p.relative_to(REPO)) for p in (REPO / "studies").glob("*.yaml"))]
#: the configurations with the most keys, whose mutants take most of the time
LARGEST = ["config/config.yaml", "studies/quanser_rotflex.yaml", "studies/shaping.yaml"]
#: collections: mappings of entries that name each other only through the lists of REFERENCES
COLLECTIONS = (("cases",), ("case_grids",), ("readings",), ("sweeps", "maps"), ("validation", "cases"))
#: the sections that list names of cases
REFERENCES = ("study.comparisons", "control.sample_time.cases", "control.robustness.cases")


def mutations(value: Any) -> list[tuple[str, Any]]:
    """Each mutation of ``value`` (module docstring): (name, new value)."""
    found: list[tuple[str, Any]] = []
    if isinstance(value, dict):
        found += [("scalar_for_mapping", 1.5), ("list_for_mapping", [1]), ("unknown_key", {**value, "unknown_key": 1})]
    elif isinstance(value, list):
        found += [("mapping_for_list", {"key": 1}), ("scalar_for_list", 1.5), ("text_for_list", "text")]
    else:
        found += [("list_for_scalar", [value]),
                  ("number_for_text", 1.5) if isinstance(value, str) else ("text_for_value", "text")]
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            found += [("negative", -abs(value) - 1), ("huge", 10**12 if isinstance(value, int) else 1e300)]
    return found + [("nan", math.nan), ("none", None), ("empty_text", ""), ("empty_list", []), ("empty_mapping", {})]


def unshared(node: Any) -> Any:
    """A copy of ``node`` in which no two places share an object (YAML aliases become copies)."""
    if isinstance(node, dict):
        return {key: unshared(value) for key, value in node.items()}
    if isinstance(node, list):
        return [unshared(value) for value in node]
    return node


def nodes(node: Any, parts: tuple = ()) -> Iterator[tuple[tuple, Any]]:
    """Every node below the root: (key parts, value)."""
    if parts:
        yield parts, node
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in items:
        yield from nodes(value, parts + (key,))


def _at(cfg: Any, parts: tuple) -> Any:
    """The value at ``parts`` in ``cfg``, None where there is none."""
    for part in parts:
        if isinstance(cfg, dict):
            cfg = cfg.get(part)
        elif isinstance(cfg, list) and isinstance(part, int) and part < len(cfg):
            cfg = cfg[part]
        else:
            return None
    return cfg


def _set(cfg: dict, parts: tuple, value: Any) -> None:
    node = cfg
    for part in parts[:-1]:
        node = node[part]
    node[parts[-1]] = value


@contextlib.contextmanager
def mutated(cfg: dict, parts: tuple, value: Any) -> Iterator[dict]:
    """``cfg`` with ``value`` at ``parts`` while the context lasts."""
    node = _at(cfg, parts[:-1])
    old = node[parts[-1]]
    node[parts[-1]] = value
    try:
        yield cfg
    finally:
        node[parts[-1]] = old


def entry_of(parts: tuple) -> tuple | None:
    """The collection entry (its key parts) ``parts`` lies in, None outside the collections."""
    for collection in COLLECTIONS:
        if parts[:len(collection)] == collection and len(parts) > len(collection):
            return parts[:len(collection) + 1]
    return None


def _shape(node: Any, parts: tuple = ()) -> frozenset:
    """The keys below ``node`` (list items as one) with the types of their values."""
    if isinstance(node, dict):
        return frozenset().union(*(_shape(v, parts + (k,)) for k, v in node.items())) | {(parts, "dict")}
    if isinstance(node, list):
        return frozenset().union(*(_shape(v, parts + ("[]",)) for v in node)) | {(parts, "list")}
    return frozenset({(parts, type(node).__name__)})


def _generated(cfg: dict, grid: str) -> set[str]:
    """The names of the cases the grid ``grid`` of ``cfg`` generates (none when it is invalid)."""
    spec = _at(cfg, ("case_grids", grid))
    if not GRIDS_VALIDATOR.is_valid({grid: spec}):
        return set()
    try:
        return set(grid_cases(spec))
    except (KeyError, ValueError, IndexError):
        return set()


def _reference_lists(cfg: dict) -> dict[tuple, list]:
    """The lists of case names of :data:`REFERENCES` in ``cfg``, by their key parts."""
    comparisons = _at(cfg, ("study", "comparisons"))
    lists = {("study", "comparisons", name): names
             for name, names in (comparisons.items() if isinstance(comparisons, dict) else ())}
    lists |= {("control", part, "cases"): _at(cfg, ("control", part, "cases"))
              for part in ("sample_time", "robustness")}
    return {parts: names for parts, names in lists.items() if isinstance(names, list)}


def _cut(grid: dict, but: int | None = None) -> None:
    """``grid``'s axes (but the axis ``but``) cut to their first values: with them all cut, it
    generates its first case only."""
    for index, axis in enumerate(grid.get("axes", [])):
        for spec in axis.values() if index != but else ():
            spec["values"] = spec["values"][:1]


def _grid_part(parts: tuple) -> tuple:
    """The part of its grid the key ``parts`` of ``case_grids`` lies in: its base case or its name
    template (all its axes cut), one of its axes (the others cut), or the grid or its axes (none cut)."""
    if parts[:1] != ("case_grids",) or len(parts) < 3 or parts[2:] == ("axes",):
        return ()
    return parts[2:4] if parts[2] == "axes" else parts[2:3]


def _related_lists(cfg: dict, parts: tuple) -> set[tuple]:
    """The lists of :func:`_reference_lists` that hold the key ``parts`` or lie below it."""
    return {where for where in _reference_lists(cfg) if where[:len(parts)] == parts or parts[:len(where)] == where}


def reduction(cfg: dict, parts: tuple) -> tuple:
    """What :func:`reduced` depends on besides ``cfg``: the entry of ``parts`` (or its section),
    the lists it keeps, and the part of a grid it lies in."""
    return entry_of(parts) or parts[:1], frozenset(_related_lists(cfg, parts)), _grid_part(parts)


def reduced(cfg: dict, parts: tuple) -> dict:
    """``cfg`` reduced to the part the key ``parts`` belongs to (module docstring)."""
    out = unshared(cfg)
    entry = entry_of(parts)
    lists = _reference_lists(cfg)
    related = _related_lists(cfg, parts)
    named = {name for where in related for name in lists[where] if isinstance(name, str)}
    if isinstance(cfg.get("products"), list) and PAPER in cfg["products"]:  # the cases the paper's products read
        named |= set(product_cases(PAPER_PRODUCTS))
    # the collection whose entries the key's checks read: its entry's, or that of its section
    active = entry[:-1] if entry else next((c for c in COLLECTIONS if c[0] == parts[0]), None)
    for collection in COLLECTIONS:
        entries = _at(out, collection)
        if not isinstance(entries, dict):
            continue
        if entry is not None:
            keep = {entry[-1]} if collection == active else set()
        elif active is None or collection == active:  # one entry of each shape
            shapes: dict = {}
            for name, value in entries.items():
                shapes.setdefault(_shape(value), name)
            keep = set(shapes.values())
        else:
            keep = set()
        if collection == ("cases",):
            keep |= named
        if collection == ("case_grids",):
            keep |= {grid for grid in entries if _generated(cfg, grid) & named}
        if collection == ("validation", "cases") and (keep or parts[0] == "validation"):
            keep.add(_at(out, ("validation", "convergence", "case")))
        _at(out, collection[:-1])[collection[-1]] = {name: value for name, value in entries.items() if name in keep}
    for grid, spec in (out.get("case_grids") or {}).items():
        if _generated(cfg, grid) & named:
            continue  # the cases the kept lists name
        if entry != ("case_grids", grid):
            _cut(spec)
        elif _grid_part(parts):
            _cut(spec, but=parts[3] if _grid_part(parts)[:1] == ("axes",) else None)
    if not out.get("cases") and not out.get("case_grids"):  # `cases` must not be empty: its first case
        first = "cases" if cfg.get("cases") else "case_grids"
        name = next(iter(cfg[first]))
        out[first] = {name: unshared(cfg[first][name])}
    for collection in COLLECTIONS[1:]:  # an emptied collection goes, with its section
        if _at(out, collection) == {} and _at(cfg, collection):
            del out[collection[0]]
    names = set(out.get("cases") or {}) | {name for grid in out.get("case_grids") or {}
                                           for name in _generated(out, grid)}
    for where in set(lists) - related:  # the other lists: the names left
        _set(out, where, [name for name in lists[where] if name in names])
    comparisons = _at(out, ("study", "comparisons"))
    if isinstance(comparisons, dict):
        out["study"]["comparisons"] = {key: value for key, value in comparisons.items()
                                       if ("study", "comparisons", key) in related or len(value) >= 2}
        if not out["study"]["comparisons"]:
            del out["study"]["comparisons"]
    control = out.get("control")
    if isinstance(control, dict):
        for part in ("sample_time", "robustness"):
            if isinstance(control.get(part), dict) and not control[part].get("cases"):
                del control[part]
        if not control:
            del out["control"]
    return out


class Base(NamedTuple):
    """A reduced configuration (:func:`reduced`), its cases and the cases each of its grids generates."""

    cfg: dict
    cases: set
    generated: dict


def base_of(cfg: dict) -> Base:
    return Base(cfg, set(cfg.get("cases") or {}), {grid: _generated(cfg, grid) for grid in cfg.get("case_grids") or {}})


def candidates(mutated: tuple, base: Base, checked: dict) -> set[str]:
    """The key paths that stand for the key ``mutated`` of ``base`` (module docstring): itself and,
    for a key of a grid, the cases the grid generates (``checked`` is the mutant as the check
    completed it, its grids' cases added)."""
    found = {key_path(list(mutated))}
    if mutated[:1] == ("case_grids",) and len(mutated) >= 2:
        cases = checked.get("cases")
        generated = base.generated.get(mutated[1], set()) | (set(cases) - base.cases if isinstance(cases, dict)
                                                             else set())
        rest = list(mutated[3:]) if mutated[2:3] == ("case",) else []
        found |= {key_path(["cases", name, *rest]) for name in generated}
    return found


def attributed(problem: Any, mutated: tuple, keys: set[str]) -> bool:
    """Whether ``problem`` names the key ``mutated`` or one of the ``keys`` that stand for it
    (:func:`candidates`; module docstring)."""
    path, _, text = str(problem).partition(": ")
    if hasattr(problem, "path"):
        path, text = problem.path, problem.text
    if any(_related(path, key) or key in text for key in keys):
        return True
    if _supplies_cases(mutated) and (path == "cases" or path.startswith(REFERENCES)):
        return True  # the cases it supplied are gone: `cases` is empty, or a name of another section is unknown
    through = mutated[:1] == ("case_grids",) and mutated[2:3] == ("case",) and len(mutated) > 3
    return through and path == key_path(list(mutated[:2]) + ["axes"]) and repr(mutated[-1]) in text


def _supplies_cases(mutated: tuple) -> bool:
    """Whether the key ``mutated`` supplies the names of cases: ``cases`` or ``case_grids`` or one
    of their entries, or a grid's name template or axes (which make its cases' names)."""
    if mutated[:1] == ("cases",):
        return len(mutated) <= 2
    return mutated[:1] == ("case_grids",) and (len(mutated) <= 2 or mutated[2] in ("name", "axes"))


def _related(path: str, key: str) -> bool:
    """``path`` is ``key``, a key below it or a mapping above it."""
    if path == key:
        return True
    shorter, longer = sorted((path, key), key=len)
    return longer.startswith(shorter) and longer[len(shorter)] in ".["


@functools.cache
def configuration(path: str) -> dict:
    return unshared(read_config_file(REPO / path))


def mutants(path: str) -> Iterator[tuple[tuple, str, Any]]:
    """Every mutant of the configuration at ``path``: (key parts, mutation, new value)."""
    for parts, value in nodes(configuration(path)):
        for name, new in mutations(value):
            yield parts, name, new


@pytest.fixture(scope="module")
def memoised_checks():
    """The check with the YAML files it rereads read once, and each case's matrices and resolution
    computed once per (case, beam, numerics) (module docstring)."""
    read, matrices, resolve = load._read_file, control_cases.case_matrices, control_cases.resolve
    memo: dict = {}

    def once(key, compute):
        if key not in memo:
            try:
                memo[key] = (True, compute())
            except control_cases.FeedbackError as error:
                memo[key] = (False, error)
        done, value = memo[key]
        if not done:
            raise value
        return value

    def read_once(file):  # the check rereads its files for their problems (repeated keys) only
        data, problems = once(("file", str(file)), lambda: read(file))
        return data, list(problems)

    def case_matrices(case, beam, numerics, given=None):
        return once(("matrices", repr(case), repr(beam), repr(numerics), given is None),
                    lambda: matrices(case, beam, numerics, given))

    def resolved(case, sm, beam):
        return once(("resolve", repr(case), repr(beam), id(sm)), lambda: resolve(case, sm, beam))

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(load, "_read_file", read_once)
        patch.setattr(control_cases, "case_matrices", case_matrices)
        patch.setattr(control_cases, "resolve", resolved)
        yield checked_configuration


@pytest.mark.parametrize("path", [path for path in CONFIG_FILES if path not in LARGEST])
def test_every_mutation_of_every_key_is_refused_by_name_or_accepted(path, memoised_checks):
    check_every_mutation(path, memoised_checks)


@pytest.mark.parametrize("path", LARGEST)
def test_every_mutation_of_every_key_of_the_largest_configurations(path, memoised_checks):
    """As :func:`test_every_mutation_of_every_key_is_refused_by_name_or_accepted`: the configurations
    with the most keys, about 25 s of the whole test's 35 s (``slow`` in tests/conftest.py)."""
    check_every_mutation(path, memoised_checks)


def check_every_mutation(path: str, memoised_checks) -> None:
    """The rule of the module docstring for every mutant of the configuration at ``path``."""
    files = [str(REPO / path)]
    bases: dict = {}
    failures, count = [], 0
    for parts, name, new in mutants(path):
        key = reduction(configuration(path), parts)
        if key not in bases:
            bases[key] = base_of(reduced(configuration(path), parts))
            _, _, problems = memoised_checks(bases[key].cfg, files)
            assert not problems, (f"{path}: the configuration reduced for {key_path(list(parts))} is invalid",
                                  problems)
        base = bases[key]
        count += 1
        try:
            with mutated(base.cfg, parts, new) as mutant:  # the check changes nothing in it
                checked, _, problems = memoised_checks(mutant, files)
        except BaseException:  # noqa: BLE001 - every exception is a failure of the check
            failures.append(f"{key_path(list(parts))} <- {name} ({new!r}): crashed\n{traceback.format_exc()}")
            continue
        keys = candidates(parts, base, checked)
        stray = [str(problem) for problem in problems if not attributed(problem, parts, keys)]
        if stray:
            failures.append(f"{key_path(list(parts))} <- {name} ({new!r}): problems naming other keys: {stray}")
    assert count > 0
    assert not failures, f"{path}: {len(failures)} of {count} mutants failed:\n" + "\n".join(failures[:200])
