"""--timeout's range (hunt 58): 1e300 was taken, and --stats' "margin to timeout ms" cell was a 300-digit
number; 1e-300 said "later than the 0 ms timeout". 1 ms (the texts' and the plugin preference's unit) to a
day (an answer later than that answers nothing)."""
from __future__ import annotations

import pytest

from conftest import ROOT
from helpers import run_cli

CAPTURE = str(ROOT / "captures" / "p38_protection.pcap")


@pytest.mark.parametrize("value", ["1e300", "1e-300", "0.0009", "86401"])
def test_outside_is_refused(value):
    assert run_cli(["--timeout", value, CAPTURE]) == (2, "", (
        f"vw3-decode: argument --timeout: '{value}' is outside 0.001..86400 seconds (1 ms to a day)"
        " (see vw3-decode --help)\n"))


@pytest.mark.parametrize("value, note", [
    ("0.001", "[warning: response 10.2 ms after request #1, later than the 1 ms timeout: not its answer]"),
    ("86400", "[#1, 10.2 ms]"),
])
def test_the_ends_are_taken(value, note):
    status, out, err = run_cli(["--timeout", value, "-c", "2", CAPTURE])
    assert (status, err) == (0, "")
    assert note in out.splitlines()[1]
