"""Filters take what the screen shows (issue 15): PLC-style addresses, 16#8000 and 0x8000 literals,
`&` bit tests, `matches` regular expressions, misspelt status/kind values named with the valid ones."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli

ROOT = Path(__file__).resolve().parents[2]
P38 = str(ROOT / "captures" / "p38_protection.pcap")
SEL = str(ROOT / "captures" / "sel749m_polling.pcap")


def _frames(*argv: str) -> list[int]:
    status, out, err = run_cli(["-T", "fields", "-e", "frame", *argv])
    assert (status, err) == (0, ""), err
    return [int(line) for line in out.splitlines()]


def test_plc_style_address_matches_the_number_shown() -> None:
    # 40002 is holding register 1: the FC3 reads of 0..15 (request and response) and the FC23 read of 0..1.
    shown = _frames("--address-style", "plc", "-Y", "address == 40002 and frame <= 44", SEL)
    assert shown == [1, 2, 5, 6, 9, 10, 15, 16, 21, 22, 25, 27, 28, 33, 34, 39, 40, 43]
    # the protocol address still works, and both name the same registers
    assert _frames("--address-style", "plc", "-Y", "address == 1 and frame <= 44", SEL) == shown
    assert _frames("--address-style", "plc", "-Y", "address in {40002..40002} and frame <= 44", SEL) == shown
    # register 300 shown as 40301: written by FC6, FC23 and FC16 (frame 49's "40303" is a third value
    # over a quantity of 2, and the FC16 confirmation 68 names 40301..40302 without values)
    assert _frames("--address-style", "plc", "-Y", "address == 40301", SEL) == [19, 20, 43, 49, 55, 67, 68]
    # without PLC style there is no 40002 on the screen, and none matches
    assert _frames("-Y", "address == 40002", SEL) == []


def test_radix_literals_as_the_notes_print_them() -> None:
    # 8400 reads 16#8000 (non-existent) in every response
    assert _frames("-Y", "value == 16#8000", P38) == [2, 4, 6, 8]
    assert _frames("-Y", "value == 0x8000", P38) == [2, 4, 6, 8]
    # CHCF = IO (3); profile auto chose the ATV71 over the whole file, frame 2 is named too (issue 27)
    assert _frames("-Y", "value == 2#11 and code == \"CHCF\"", P38) == [2, 4]


def test_bit_test() -> None:
    assert _frames("-Y", "value & 0x8000", P38) == [2, 4, 6, 8]
    assert _frames("-Y", "code == \"COP\" and value & 16#0002", P38) == [2, 4, 6, 8]
    assert _frames("-Y", "code == \"COP\" and value & 1", P38) == []


def test_matches_is_a_case_insensitive_regular_expression_as_in_wireshark() -> None:
    assert _frames("-Y", 'notes matches "BECAME (protected|non-existent)"', P38) == [6, 10]
    assert _frames("-Y", 'notes ~ "(?-i)BECAME"', P38) == []
    # 10, 12: exception 02 tells COP; frame 2 is named (auto chose over the whole file: issue 27)
    assert _frames("-Y", 'code matches "^C.P$"', P38) == [2, 4, 6, 8, 10, 12]


@pytest.mark.parametrize(
    ("expression", "message"),
    [
        ('status == "protect"',
         "status 'protect' does not exist (did you mean 'protected'?): "
         "status is one of ok, protected, non-existent, ambiguous (column 11)"),
        ('kind == "responce"',
         "kind 'responce' does not exist (did you mean 'response'?): "
         "kind is one of request (1), response (2), exception (3), noise (4) (column 9)"),
        ("value & 1.5", "& needs a whole-number mask such as 0x8000 (column 9)"),
        ('code & 1', "& tests bits of a number; code is a text (column 6)"),
        ("value == 3#12", "3#12: the radix before # is 2, 8 or 16 (column 10)"),
        ("value == 16#80G0", "16#80G0: '80G0' are not base-16 digits (column 10)"),
        ('notes matches "("', "not a regular expression: missing ), unterminated subpattern at position 0 (column 15)"),
        ('value matches "1"', "matches needs a text field; value is a number (column 7)"),
    ],
)
def test_filter_mistakes_are_named(expression: str, message: str) -> None:
    status, out, err = run_cli(["-Y", expression, P38])
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == f"vw3-decode: {message}"
