"""The one reader of the CSV tables a config may name instead of inline lists.

Three entries of a config accept ``{file: <path>}`` (the path relative to the config file) in
place of inline lists:

* ``beam.sections``: header ``x,rhoA,EI,EA`` (stations of the non-uniform beam);
* a maneuver of kind ``speed_table`` (header ``time,speed``) or ``torque_table``
  (``time,torque``): ``{kind: speed_table, file: profile.csv}``;
* the ``reference`` of a ``pd`` maneuver of kind ``angle_table`` (header ``time,angle``).

:func:`resolve_files` replaces each such entry by the inline lists before the config is
validated, so every later step sees one form. A table file is plain CSV: one header line naming
exactly the columns above (in any order), then one row of numbers per line; blank lines and lines
starting with ``#`` are skipped; a UTF-8 byte-order mark and CRLF line ends, as spreadsheets
write them, are accepted. A missing file, a wrong header, a row of the wrong length or a value
that is not a number is reported with the file and the line, naming a ``;`` separator or a
decimal comma when one is the cause; characters that would not show are escaped in messages.
"""

from __future__ import annotations

import copy
import csv
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.schema import Problem
from hubbeam.model.maneuvers import TABLES

#: columns of the beam's station table
SECTION_COLUMNS = ("x", "rhoA", "EI", "EA")
#: maneuver (or controller reference) kind -> columns of its table (the tabulated records of
#: :mod:`hubbeam.model.maneuvers`)
PROFILE_COLUMNS = {kind: ("time", record.column) for kind, record in TABLES.items()}


class TableError(ValueError):
    """A CSV table cannot be read; the message names the file and, where it applies, the line."""


def read_table(path: os.PathLike | str, columns: tuple[str, ...]) -> dict[str, list[float]]:
    """The columns of the CSV file ``path`` as ``{name: [float, ...]}`` (order of the file).

    The file is read as a spreadsheet saves "CSV UTF-8": a byte-order mark at its start and
    CRLF line ends are accepted. Values separated by ``;`` or written with a decimal comma (the
    "CSV" of several locales) are reported as such, with the line.
    """
    where = f"file {shown(str(path))}"
    rows = read_rows(path, f"a readable CSV file with the header {','.join(columns)}")
    if not rows:
        raise TableError(f"{where}: empty; allowed: the header {','.join(columns)} and rows of numbers")
    line, header = rows[0]
    header = [cell.strip() for cell in header]
    if sorted(header) != sorted(columns):
        raise TableError(f"{where}, line {line}: header {shown(','.join(header))}; allowed: the "
                         f"columns {','.join(columns)} (any order), each once"
                         + separator_hint(header, len(columns)))
    table: dict[str, list[float]] = {name: [] for name in header}
    for line, row in rows[1:]:
        if len(row) != len(header):
            raise TableError(f"{where}, line {line}: {len(row)} values; allowed: "
                             f"{len(header)} ({','.join(header)})" + separator_hint(row, len(header)))
        for name, cell in zip(header, row):
            table[name].append(parse_number(cell, f"{where}, line {line}, column {name}"))
    if not rows[1:]:
        raise TableError(f"{where}: no rows after the header; allowed: at least one row of numbers")
    return {name: table[name] for name in columns}


def read_rows(path: os.PathLike | str, allowed: str) -> list[tuple[int, list[str]]]:
    """The lines of the CSV file ``path`` that hold values, each as ``(line number, cells)``, the
    header first: blank lines and lines starting with ``#`` skipped, a byte-order mark and CRLF
    line ends accepted. A file that cannot be read or is not UTF-8 is a :class:`TableError`
    naming it (``allowed``: what the file should be). The one reading of every table, so that
    other readers (``hubbeam.identification.files``) accept and report files as :func:`read_table` does."""
    path = Path(path)
    where = f"file {shown(str(path))}"
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as error:
        raise TableError(f"{where}: cannot be read ({error.strerror or error}); allowed: {allowed}") from None
    except UnicodeDecodeError as error:
        raise TableError(f"{where}: not UTF-8 text (byte {error.start}); allowed: a CSV file saved "
                         "as UTF-8 (a spreadsheet's \"CSV UTF-8\")") from None
    return [(number, row) for number, row in enumerate(csv.reader(text.splitlines()), start=1)
            if row and not row[0].lstrip().startswith("#") and any(cell.strip() for cell in row)]


def separator_hint(cells: list[str], expected: int) -> str:
    """Why a line of ``cells`` may not split into ``expected`` values: ``;`` separators, or
    decimal commas that split numbers in two."""
    if any(";" in cell for cell in cells):
        return ("; the values are separated by ';': write the file with ',' between values and "
                "'.' as the decimal point (a spreadsheet's \"CSV UTF-8 (comma delimited)\")")
    if len(cells) > expected and all(_is_number(cell) for cell in cells):
        return ("; if a decimal comma split a number in two, write '.' as the decimal point "
                "(1.2, not 1,2)")
    return ""


def shown(text: str) -> str:
    """``text`` with every character that would not show (a byte-order mark, a non-breaking space,
    a control character) escaped as Python writes it (``\\ufeff``)."""
    return "".join(char if char.isprintable() else ascii(char)[1:-1] for char in text)


def resolve_files(cfg: Any, base_dir: os.PathLike | str) -> dict:
    """A copy of ``cfg`` with every ``file:`` table inlined (paths relative to ``base_dir``).

    Raises :class:`hubbeam.configuration.load.ConfigError` listing every table that cannot be read, each
    under its key path. Entries of an unexpected shape are left for the schema to report.
    """
    if not isinstance(cfg, Mapping):
        return cfg
    resolved = copy.deepcopy(dict(cfg))
    problems = []
    beam = resolved.get("beam")
    if isinstance(beam, dict):
        problems += _inline(beam, "sections", SECTION_COLUMNS, "beam.sections", base_dir)
    cases = resolved.get("cases")
    for name, case in (cases.items() if isinstance(cases, dict) else ()):
        maneuver = case.get("maneuver") if isinstance(case, dict) else None
        if not isinstance(maneuver, dict):
            continue
        where = f"cases.{name}.maneuver"
        if _tabulated(maneuver):
            problems += _inline_profile(maneuver, where, base_dir)
        reference = maneuver.get("reference")
        if isinstance(reference, dict) and _tabulated(reference):
            problems += _inline_profile(reference, f"{where}.reference", base_dir)
    if problems:
        raise ConfigError(problems)
    return resolved


def _tabulated(entry: dict) -> bool:
    """Whether a maneuver or reference is of a tabulated kind (a kind that is not text is the schema's
    to refuse)."""
    kind = entry.get("kind")
    return isinstance(kind, str) and kind in PROFILE_COLUMNS


def _inline_profile(entry: dict, where: str, base_dir) -> list[Problem]:
    """Replace the ``file`` of a table-driven maneuver (or reference) by its columns."""
    if "file" not in entry:
        return []
    columns = PROFILE_COLUMNS[entry["kind"]]
    given = [key for key in columns if key in entry]
    if given:
        return [Problem(f"{where}.file", f"given together with {', '.join(given)}; allowed: "
                        f"either file or the inline lists {', '.join(columns)}")]
    source = entry.pop("file")
    try:
        entry.update(read_table(_located(source, base_dir), columns))
    except (TableError, TypeError) as error:
        return [Problem(f"{where}.file", str(error))]
    return []


def _inline(parent: dict, key: str, columns: tuple[str, ...], where: str, base_dir) -> list[Problem]:
    """Replace ``parent[key] = {file: path}`` by the table's columns."""
    entry = parent.get(key)
    if not isinstance(entry, dict) or "file" not in entry:
        return []
    if len(entry) > 1:
        others = ", ".join(sorted(k for k in entry if k != "file"))
        return [Problem(f"{where}.file", f"given together with {others}; allowed: either file "
                        f"alone or the inline lists {', '.join(columns)}")]
    try:
        parent[key] = read_table(_located(entry["file"], base_dir), columns)
    except (TableError, TypeError) as error:
        return [Problem(f"{where}.file", str(error))]
    return []


def _located(source: Any, base_dir) -> Path:
    if not isinstance(source, str) or not source:
        raise TypeError(f"got {source!r}; allowed: the path of a CSV file relative to the config file")
    return Path(base_dir, source)


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def parse_number(cell: str, where: str) -> float:
    """``cell`` as a finite float; a :class:`TableError` naming ``where`` (file, line, column), the cell and a
    decimal comma when one is the cause."""
    text = shown(cell.strip())
    try:
        value = float(cell)
    except ValueError:
        comma = (" (a decimal comma: write '.' as the decimal point, 1.2 not 1,2)"
                 if _is_number(cell.replace(",", ".", 1)) else "")
        raise TableError(f"{where}: '{text}' is not a number{comma}; allowed: a decimal "
                         "number such as 1.2e+4") from None
    if not math.isfinite(value):
        raise TableError(f"{where}: '{text}'; allowed: a finite number")
    return value
