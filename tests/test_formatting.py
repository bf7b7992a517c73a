"""The number formats of the reports (hubbeam.reporting.formatting) and the Markdown table renderer."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hubbeam.reporting.document import markdown_table, markdown_to_html
from hubbeam.reporting.formatting import csv_cell, fixed, is_missing, number, percent, scientific


@pytest.mark.parametrize("missing", [None, "", math.nan, np.float64("nan")])
def test_a_missing_value_is_a_dash_everywhere_and_an_empty_csv_cell(missing):
    assert is_missing(missing)
    assert number(missing) == fixed(missing, 2) == scientific(missing, 1) == percent(missing) == "-"
    assert csv_cell(missing) == ""


def test_significant_digits_flags_integers_and_text():
    assert number(2.6043, 4) == "2.604" and number(0.000123456, 3) == "0.000123"
    assert number(1.5e-5) == "1.5e-05"
    assert number(1.5e-5, power="unicode") == "1.5×10^-5"
    assert number(6.8952e10, 5, power="latex") == "$6.8952\\times10^{10}$"
    assert number(12345678) == "12345678" and number(np.int64(3)) == "3"
    assert number(True) == "yes" and number(False) == "no"
    assert number("FOAM") == "FOAM" and number(0) == "0" and not is_missing(0.0)
    with pytest.raises(ValueError, match="power: got 'tex'; allowed: e, unicode, latex"):
        number(1.0, power="tex")


def test_decimals_and_percentages():
    assert fixed(3.9, 6) == "3.900000" and fixed(0.25, 1, signed=True) == "+0.2"
    assert scientific(-0.00042, 1, signed=True) == "-4.2e-04"
    assert percent(0.00045) == "0.045 %" and percent(2.07) == "207 %" and percent(0.0999) == "10 %"
    assert percent(0.12345, 2) == "12 %" and percent(12.34, 3) == "1234 %"  # never 1.23e+03 %
    assert percent(-0.000518, decimals=2, signed=True) == "-0.05 %"
    assert percent(0.00187, 3, signed=True) == "+0.187 %"


def test_csv_cells_read_back_bit_for_bit():
    value = 0.1 + 0.2
    assert float(csv_cell(value)) == value and csv_cell(np.float64(value)) == repr(value)
    assert csv_cell(np.int64(7)) == "7" and csv_cell("agrees") == "agrees"


def test_a_table_has_a_header_an_aligned_separator_and_one_line_per_row():
    text = markdown_table(("case", "peak (m)", "verdict"), [["a", 0.123456, "**agrees**"], ["b", math.nan, "x"]],
                          "lrc")
    assert text.splitlines() == ["| case | peak (m) | verdict |", "|---|---:|:---:|",
                                 "| a | 0.1235 | **agrees** |", "| b | - | x |"]
    assert markdown_table(("a", "b"), []).splitlines() == ["| a | b |", "|---|---|"]


def test_a_pipe_or_a_line_break_in_a_cell_does_not_split_the_table(tmp_path):
    text = markdown_table(("claim", "n"), [["max |Q_theta| / tau_m", 3], ["two\nlines", 4]], "lr")
    assert "| max \\|Q_theta\\| / tau_m | 3 |" in text and "| two lines | 4 |" in text
    page = markdown_to_html(text, tmp_path)
    assert page.count("<tr>") == 3 and "<td>max |Q_theta| / tau_m</td>" in page


def test_a_table_with_the_wrong_shape_is_refused():
    with pytest.raises(ValueError, match="align: got 'lx' for 2 columns; allowed: one of l, r, c per column"):
        markdown_table(("a", "b"), [], "lx")
    with pytest.raises(ValueError, match=r"table row \['1'\]: 1 cells; allowed: 2 \(a, b\)"):
        markdown_table(("a", "b"), [["1"]])
