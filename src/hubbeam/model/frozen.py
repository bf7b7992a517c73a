"""Immutable values for the settings objects: a read-only mapping and a converter to it.

The settings of a checked configuration (``hubbeam.configuration.settings``) are frozen dataclasses
that the workflow hands to its jobs (Snakemake pickles them into a job's script) and whose ``repr``
Snakemake compares to decide what to rerun. ``types.MappingProxyType`` cannot be pickled, hence
:class:`FrozenMap`: a mapping that cannot be changed after it is made, that pickles, compares and
hashes by its items, and whose ``repr`` is that of the plain dict (stable across runs).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any


class FrozenMap(Mapping):
    """A read-only mapping in the order its items were given."""

    __slots__ = ("_items",)

    def __init__(self, items: Mapping | None = None):
        object.__setattr__(self, "_items", dict(items or {}))

    def __getitem__(self, key):
        return self._items[key]

    def __iter__(self) -> Iterator:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __hash__(self) -> int:
        return hash(tuple(self._items.items()))

    def __eq__(self, other) -> bool:
        return isinstance(other, Mapping) and dict(self._items) == dict(other)

    def __repr__(self) -> str:
        return repr(self._items)

    def __setattr__(self, name, value):
        raise AttributeError("FrozenMap is read-only")

    def __reduce__(self):
        return FrozenMap, (self._items,)


def freeze(value: Any) -> Any:
    """``value`` with every mapping made a :class:`FrozenMap` and every list a tuple, recursively;
    numbers stay as they are (the schema has checked them)."""
    if isinstance(value, Mapping):
        return FrozenMap({key: freeze(item) for key, item in value.items()})
    if isinstance(value, (list, tuple)):
        return tuple(freeze(item) for item in value)
    return value


def thaw(value: Any) -> Any:
    """The plain form of a frozen ``value``: dicts and lists, as written in a configuration."""
    if isinstance(value, Mapping):
        return {key: thaw(item) for key, item in value.items()}
    if isinstance(value, tuple):
        return [thaw(item) for item in value]
    return value
