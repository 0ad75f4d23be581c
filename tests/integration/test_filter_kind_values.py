"""`kind` in a display filter takes what a user types for the plugin's vw3.kind, a number with value strings
(lua/src/pack.lua NUMBER_KIND: 1 request, 2 response, 3 exception, 4 noise): the number, the name quoted or
bare in any case, ordered by number (`kind > 2`), and a value that is none of them is refused in one line
naming the valid ones with their numbers. Before, `kind == 2` said `kind is a text, not '2' (strings go in
double quotes: "...")`, `kind == Response` was refused, and `kind > "request"` compared the names as texts."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import lua_errors, run_tshark

pytestmark = pytest.mark.integration

CAPTURES = Path(__file__).resolve().parents[2] / "captures"
P38 = CAPTURES / "p38_protection.pcap"  # requests 1, 3, ... 11; responses 2, 4, 6, 8; exceptions 10, 12
VALUES = "request (1), response (2), exception (3), noise (4)"


@pytest.mark.parametrize(("expression", "frames"), [
    ("kind == 2", [2, 4, 6, 8]),
    ("kind == response", [2, 4, 6, 8]),
    ('kind == "Response"', [2, 4, 6, 8]),
    ("kind > 2", [10, 12]),
    ('kind >= "exception"', [10, 12]),
    ("kind <= request", [1, 3, 5, 7, 9, 11]),
    ('kind in {2, "EXCEPTION"}', [2, 4, 6, 8, 10, 12]),
    ("kind != 1", [2, 4, 6, 8, 10, 12]),
])
def test_kind_takes_numbers_and_names_as_the_plugin(expression: str, frames: list[int]) -> None:
    status, out, err = run_cli([str(P38), "-Y", expression, "-T", "fields", "-e", "frame"])
    assert (status, err) == (0, "")
    assert [int(n) for n in out.split()] == frames
    got = run_tshark(P38, "-Y", f"vw3.{expression}", "-T", "fields", "-e", "vw3.item")
    assert not lua_errors(got.stdout + got.stderr)
    assert [int(n) for n in got.stdout.split()] == frames


@pytest.mark.parametrize(("expression", "said"), [
    ("kind == 5", f"kind 5 does not exist: kind is one of {VALUES} (column 9)"),
    ('kind == "bogus"', f"kind 'bogus' does not exist: kind is one of {VALUES} (column 9)"),
    ("kind == respnse", f"kind 'respnse' does not exist (did you mean 'response'?): kind is one of {VALUES} (column 9)"),
    ("kind < bogus", f"kind 'bogus' does not exist: kind is one of {VALUES} (column 8)"),
])
def test_a_kind_that_is_none_is_refused_naming_the_values(expression: str, said: str) -> None:
    status, out, err = run_cli([str(P38), "-Y", expression])
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == f"vw3-decode: {said}"


def test_the_numbers_are_the_plugins() -> None:
    """Each item's kind and the plugin's vw3.kind for it: the same value, by NUMBERED's order."""
    noisy = CAPTURES / "noisy_bus.pcap"
    status, out, err = run_cli([str(noisy), "-T", "fields", "-e", "frame", "-e", "kind"])
    assert status == 0, err
    number = {"request": "1", "response": "2", "exception": "3", "noise": "4"}
    ours = [(line.split("\t")[0], number[line.split("\t")[1]]) for line in out.splitlines()]
    got = run_tshark(noisy, "-T", "fields", "-e", "vw3.item", "-e", "vw3.kind")
    theirs = [tuple(line.split("\t")) for line in got.stdout.splitlines()]
    assert ours == theirs and {kind for _, kind in ours} == {"1", "2", "4"}
