"""How the reports, tables and figures write a number: the one place for digits and missing values.

Every function returns ``"-"`` for a missing value (None, an empty cell, NaN), so that a table
cell, a sentence or a legend never shows ``nan``. Flags are ``yes``/``no``, integers are written
in full, and floats get the significant digits (:func:`number`), decimals (:func:`fixed`,
:func:`scientific`) or percentage (:func:`percent`) the caller asks for. A power of ten is written
as Python does (``1.5e-05``), or as ``1.5×10^-5`` / ``$1.5\\times10^{-5}$`` for the paper's tables
(``power="unicode"`` / ``"latex"``).
"""

from __future__ import annotations

import math
import numbers

MISSING = "-"
POWERS = ("e", "unicode", "latex")


def is_missing(value) -> bool:
    """None, an empty string or a NaN."""
    if value is None or (isinstance(value, str) and value == ""):
        return True
    return isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral) and math.isnan(value)


def number(value, digits: int = 4, *, power: str = "e") -> str:
    """``value`` to ``digits`` significant figures (``format(value, ".4g")``); ``yes``/``no`` for
    a flag, integers in full, text unchanged, ``-`` when missing. ``power`` writes a power of ten
    (one of :data:`POWERS`)."""
    if power not in POWERS:
        raise ValueError(f"power: got {power!r}; allowed: {', '.join(POWERS)}")
    if is_missing(value):
        return MISSING
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if not isinstance(value, numbers.Real):
        return str(value)
    text = f"{float(value):.{digits}g}"
    mantissa, _, exponent = text.partition("e")
    if not exponent or power == "e":
        return text
    if power == "latex":
        return f"${mantissa}\\times10^{{{int(exponent)}}}$"
    return f"{mantissa}×10^{int(exponent)}"


def csv_cell(value) -> str:
    """A cell of a result csv: a number in full precision (``repr`` of a float, so that it reads
    back bit for bit), an empty cell when missing, text unchanged."""
    if is_missing(value):
        return ""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    return str(value)


def fixed(value, decimals: int, *, signed: bool = False) -> str:
    """``value`` with ``decimals`` digits after the point (``+`` on positive values if
    ``signed``), ``-`` when missing."""
    if is_missing(value):
        return MISSING
    return f"{float(value):{'+' if signed else ''}.{decimals}f}"


def scientific(value, decimals: int, *, signed: bool = False) -> str:
    """``value`` as ``1.2e-03`` with ``decimals`` digits after the point, ``-`` when missing."""
    if is_missing(value):
        return MISSING
    return f"{float(value):{'+' if signed else ''}.{decimals}e}"


def percent(fraction, digits: int = 2, *, decimals: int | None = None, signed: bool = False) -> str:
    """``fraction`` as a percentage to ``digits`` significant figures: ``0.00045`` -> ``"0.045 %"``;
    a value of ``10^(digits-1)`` % or more is rounded to a whole percent, never written with a
    power of ten (``2.07`` -> ``"207 %"``). With ``decimals``, that many digits after the point
    instead (``-0.0005`` -> ``"-0.05 %"``). ``-`` when missing."""
    if is_missing(fraction):
        return MISSING
    value = 100.0 * float(fraction)
    sign = "+" if signed else ""
    if decimals is not None:
        return f"{value:{sign}.{decimals}f} %"
    if abs(value) >= 10.0 ** (digits - 1):
        return f"{value:{sign}.0f} %"
    return f"{value:{sign}.{digits}g} %"
