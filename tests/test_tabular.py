"""CSV tables as spreadsheets write them: a UTF-8 byte-order mark and CRLF line ends are read;
`;` separators and decimal commas get a message that says so and names the line; a character
that would not show appears escaped in every message."""

from __future__ import annotations

from pathlib import Path

import pytest

from hubbeam.configuration.tabular import SECTION_COLUMNS, TableError, read_table, resolve_files

PLAIN = "x,rhoA,EI,EA\n0,1.2,14000,2.8e7\n10,1.2,14000,2.8e7\n"
EXPECTED = {"x": [0.0, 10.0], "rhoA": [1.2, 1.2], "EI": [14000.0, 14000.0], "EA": [2.8e7, 2.8e7]}


def write_bytes(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


def message_of(path: Path) -> str:
    with pytest.raises(TableError) as caught:
        read_table(path, SECTION_COLUMNS)
    message = str(caught.value)
    assert message.isprintable(), message  # nothing invisible in what the user reads
    return message


@pytest.mark.parametrize("data", [
    PLAIN.encode(),
    b"\xef\xbb\xbf" + PLAIN.encode(),                          # "CSV UTF-8": byte-order mark
    PLAIN.replace("\n", "\r\n").encode(),                      # Windows line ends
    b"\xef\xbb\xbf" + PLAIN.replace("\n", "\r\n").encode(),    # both, as Excel writes it
])
def test_a_spreadsheets_csv_is_read(tmp_path, data):
    assert read_table(write_bytes(tmp_path / "beam.csv", data), SECTION_COLUMNS) == EXPECTED


def test_a_bom_and_crlf_sections_file_resolves_in_a_config(tmp_path):
    write_bytes(tmp_path / "beam.csv", b"\xef\xbb\xbf" + PLAIN.replace("\n", "\r\n").encode())
    resolved = resolve_files({"beam": {"sections": {"file": "beam.csv"}}}, tmp_path)
    assert resolved["beam"]["sections"] == EXPECTED


def test_semicolon_separators_are_named_with_the_line(tmp_path):
    text = "# beam\r\nx;rhoA;EI;EA\r\n0;1.2;14000;2.8e7\r\n"
    message = message_of(write_bytes(tmp_path / "semi.csv", b"\xef\xbb\xbf" + text.encode()))
    assert "line 2" in message
    assert "separated by ';'" in message and "','" in message


def test_semicolons_and_decimal_commas_of_a_locale_are_named(tmp_path):
    text = "x;rhoA;EI;EA\n0;1,2;14000;2,8e7\n"
    message = message_of(write_bytes(tmp_path / "locale.csv", text.encode()))
    assert "line 1" in message and "separated by ';'" in message


def test_a_semicolon_row_under_a_comma_header_is_named(tmp_path):
    message = message_of(write_bytes(tmp_path / "mixed.csv", b"x,rhoA,EI,EA\n0;1.2;14000;2.8e7\n"))
    assert "line 2" in message and "1 values" in message and "separated by ';'" in message


def test_an_unquoted_decimal_comma_is_suspected(tmp_path):
    message = message_of(write_bytes(tmp_path / "comma.csv", b"x,rhoA,EI,EA\n0,1,2,14000,2.8e7\n"))
    assert "line 2" in message and "5 values" in message and "decimal comma" in message


def test_a_quoted_decimal_comma_is_named(tmp_path):
    message = message_of(write_bytes(tmp_path / "quoted.csv", b'x,rhoA,EI,EA\n0,"1,2",14000,2.8e7\n'))
    assert "line 2, column rhoA" in message and "'1,2' is not a number" in message
    assert "decimal comma" in message


def test_a_row_too_short_is_not_blamed_on_commas(tmp_path):
    message = message_of(write_bytes(tmp_path / "short.csv", b"x,rhoA,EI,EA\n0,1,2\n"))
    assert "3 values" in message and "decimal comma" not in message and "';'" not in message


@pytest.mark.parametrize("data, shown", [
    (b"\xef\xbb\xbf\xef\xbb\xbf" + PLAIN.encode(), r"\ufeffx,rhoA"),        # a second mark
    ("x,rho\u200bA,EI,EA\n0,1,2,3\n".encode(), r"x,rho\u200bA"),            # zero-width space
])
def test_an_invisible_character_in_the_header_is_shown_escaped(tmp_path, data, shown):
    message = message_of(write_bytes(tmp_path / "hidden.csv", data))
    assert "line 1" in message and f"header {shown}" in message


def test_an_invisible_character_in_a_value_is_shown_escaped(tmp_path):
    message = message_of(write_bytes(tmp_path / "value.csv", "x,rhoA,EI,EA\n0,1.2\u200b,2,3\n".encode()))
    assert r"'1.2\u200b' is not a number" in message


def test_a_file_that_is_not_utf8_is_named(tmp_path):
    message = message_of(write_bytes(tmp_path / "latin1.csv", "x,rhoA,EI,EA\n0,1,2,3 µ\n".encode("latin-1")))
    assert "not UTF-8" in message
