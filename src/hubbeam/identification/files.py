"""Experiment files: CSV tables whose header names every column with its unit, ``name [unit]``.

A rig's data logger writes tables; an experiment file is one of them, read like every other table
of hubbeam (:func:`hubbeam.configuration.tabular.read_rows`: UTF-8 with or without a byte-order
mark, CRLF accepted, blank lines and ``#`` comment lines skipped, ``;`` separators and decimal
commas named). The header line gives each column as ``name [unit]`` (``time [s]``, ``frequency
[Hz]``, ``hub_angle [rad]``), so that a file measured in other units is refused rather than
misread. Every refusal is an :class:`ExperimentError` naming the file, the line, the column and
what is allowed: a header cell without a unit, a column the experiment does not know, a column
given twice, a required column missing, a unit not among the allowed ones, a row of the wrong
length, a value that is not a finite number (NaN and inf included), too few rows, and (by
:func:`check_increasing`) a column that does not increase.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubbeam.configuration.tabular import TableError, parse_number, read_rows, separator_hint, shown

#: a header cell: a name, then its unit in square brackets
HEADER_CELL = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*\[([^\[\]]*)\]\s*$")


class ExperimentError(TableError):
    """An experiment file or record is refused; the message names the file (or the record), the
    line, the column and what is allowed."""


@dataclass(frozen=True)
class ColumnSpec:
    """A column an experiment file may hold: its ``name``, the ``units`` it may be written in
    (UDUNITS spelling, as ``hubbeam.linear.statespace.OUTPUTS``) and whether it is ``required``."""

    name: str
    units: tuple[str, ...]
    required: bool = True

    def header(self) -> str:
        """The header cell in the first allowed unit, ``name [unit]``."""
        return header_cell(self.name, self.units[0])


def header_cell(name: str, unit: str) -> str:
    """``name [unit]``."""
    return f"{name} [{unit}]"


def _unit(text: str) -> str:
    return " ".join(text.split())


@dataclass(frozen=True, eq=False)
class Table:
    """The columns of an experiment file: ``values`` and ``units`` by name (the units as written),
    the file's line number of every row (``lines``) and of the header."""

    path: str
    values: Mapping[str, np.ndarray]
    units: Mapping[str, str]
    lines: np.ndarray
    header_line: int

    def where(self, column: str | None = None, row: int | None = None) -> str:
        """``file <path>[, line <n>][, column <name>]`` for messages (``row`` indexes the rows)."""
        text = f"file {shown(self.path)}"
        if row is not None:
            text += f", line {int(self.lines[row])}"
        elif column is not None:
            text += f", line {self.header_line}"
        return text + ("" if column is None else f", column {column}")


def _allowed_header(columns: Sequence[ColumnSpec]) -> str:
    required = ", ".join(spec.header() for spec in columns if spec.required)
    optional = [spec.header() for spec in columns if not spec.required]
    return f"a header with {required}" + (f" (optional: {', '.join(optional)})" if optional else "")


def read_columns(path: os.PathLike | str, columns: Sequence[ColumnSpec], minimum_rows: int, what: str) -> Table:
    """The :class:`Table` of the experiment file ``path`` holding the ``columns`` (any order; the
    optional ones may be left out) and at least ``minimum_rows`` rows; ``what`` names the kind of
    experiment in messages. Refusals: module docstring."""
    path = str(path)
    where = f"file {shown(path)}"
    specs = {spec.name: spec for spec in columns}
    try:
        rows = read_rows(path, f"a readable CSV file of {what} with {_allowed_header(columns)}")
    except TableError as error:
        raise ExperimentError(str(error)) from None
    if not rows:
        raise ExperimentError(f"{where}: empty; allowed: {_allowed_header(columns)}, then rows of numbers")
    header_line, cells = rows[0]
    names, units = [], {}
    for cell in cells:
        found = HEADER_CELL.match(cell)
        if found is None:
            name = cell.strip()
            hint = (f"; allowed: {specs[name].header()}" if name in specs
                    else f"; allowed: {_allowed_header(columns)}" + separator_hint(cells, len(specs)))
            raise ExperimentError(f"{where}, line {header_line}, column {shown(name)!r}: no unit in square "
                                  f"brackets{hint}")
        name, unit = found.group(1), _unit(found.group(2))
        if name not in specs:
            raise ExperimentError(f"{where}, line {header_line}, column {shown(cell.strip())!r}: not a column of "
                                  f"{what}; allowed: {_allowed_header(columns)}")
        if name in units:
            raise ExperimentError(f"{where}, line {header_line}, column {name}: given twice; allowed: each "
                                  "column once")
        if unit not in specs[name].units:
            raise ExperimentError(f"{where}, line {header_line}, column {name}: unit {shown(unit)!r}; allowed: "
                                  f"{' or '.join(repr(allowed) for allowed in specs[name].units)}")
        names.append(name)
        units[name] = unit
    missing = [spec.header() for spec in columns if spec.required and spec.name not in units]
    if missing:
        raise ExperimentError(f"{where}, line {header_line}: no column {', '.join(missing)}; allowed: "
                              f"{_allowed_header(columns)}")
    data = rows[1:]
    values = np.empty((len(data), len(names)))
    for k, (line, row) in enumerate(data):
        if len(row) != len(names):
            raise ExperimentError(f"{where}, line {line}: {len(row)} values; allowed: {len(names)} "
                                  f"({', '.join(names)})" + separator_hint(row, len(names)))
        for j, (name, cell) in enumerate(zip(names, row)):
            try:
                values[k, j] = parse_number(cell, f"{where}, line {line}, column {name}")
            except TableError as error:
                raise ExperimentError(str(error)) from None
    if len(data) < minimum_rows:
        raise ExperimentError(f"{where}: {len(data)} rows of values; allowed: at least {minimum_rows} rows of {what}")
    return Table(path=path, values={name: values[:, j] for j, name in enumerate(names)}, units=units,
                 lines=np.array([line for line, _ in data]), header_line=header_line)


def check_increasing(table: Table, column: str) -> None:
    """An :class:`ExperimentError` at the first row where ``column`` does not increase strictly."""
    values = table.values[column]
    steps = np.diff(values)
    bad = np.flatnonzero(~(steps > 0.0))
    if bad.size:
        k = int(bad[0]) + 1
        raise ExperimentError(f"{table.where(column, k)}: {float(values[k])!r} after {float(values[k - 1])!r}; "
                              "allowed: values increasing strictly down the file")


def check_range(table: Table, column: str, low: float, high: float, allowed: str, include_low: bool = True,
                include_high: bool = True) -> None:
    """An :class:`ExperimentError` at the first row where ``column`` leaves ``[low, high]`` (ends
    included or not as said); ``allowed`` words the range."""
    values = table.values[column]
    below = values < low if include_low else values <= low
    above = values > high if include_high else values >= high
    bad = np.flatnonzero(below | above)
    if bad.size:
        k = int(bad[0])
        raise ExperimentError(f"{table.where(column, k)}: {float(values[k])!r}; allowed: {allowed}")


def write_columns(path: os.PathLike | str, columns: Mapping[str, tuple[str, np.ndarray]],
                  comments: Sequence[str] = (), digits: int = 7) -> Path:
    """Write an experiment file: ``# comments``, the header ``name [unit], ...`` and the rows, each
    value with ``digits`` significant digits (``columns``: name -> (unit, values), in order)."""
    path = Path(path)
    arrays = [np.asarray(values, dtype=float) for _, values in columns.values()]
    if any(not np.all(np.isfinite(values)) for values in arrays):
        raise ValueError(f"write_columns({str(path)!r}): a value that is not finite; allowed: finite values")
    lines = [f"# {comment}" for comment in comments]
    lines.append(",".join(header_cell(name, unit) for name, (unit, _) in columns.items()))
    lines += [",".join(_number_text(value, digits) for value in row) for row in zip(*arrays)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _number_text(value: float, digits: int) -> str:
    text = f"{value:.{digits}g}"
    return "0" if text in ("-0", "0") else text


def uniform_step(table: Table, column: str, tolerance: float = 1e-3) -> float:
    """The step of ``column``, whose values must be equally spaced (a logger's sample times) to
    ``tolerance`` of the step; an :class:`ExperimentError` at the first row off the grid."""
    values = table.values[column]
    step = float(np.median(np.diff(values)))
    off = np.abs(values - (values[0] + step * np.arange(values.size))) > tolerance * step
    bad = np.flatnonzero(off)
    if bad.size or not (math.isfinite(step) and step > 0.0):
        k = int(bad[0]) if bad.size else 0
        raise ExperimentError(f"{table.where(column, k)}: {float(values[k])!r} is off the grid of step {step:.6g}; "
                              "allowed: equally spaced sample times")
    return float(step)
