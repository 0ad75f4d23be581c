"""A record's later items are no evidence of a wrong line speed (bustiming.same_stamp_overlaps).

The sigrok-dumps wizmodbus bus channel (tests/corpus/SOURCES.md) is a real 9600 baud line whose transceiver
leaves one glitch byte after every frame, in the same burst as the frame: the dump line (or pcap record)
stamps its first byte, so the glitch is stamped at the frame's own start and "overlaps" it at any speed.
--stats --baud 9600, the line's measured speed, warned `88 frames would overlap the one before at 9600
baud: the line is faster?` and --json said overlaps 88; a truly wrong speed is still said, counting the
frames alone (86 at 1200 baud, as the RX/TX channels without glitches give). Engine and Python stages alike.
"""
from __future__ import annotations

import json

import pytest

from conftest import ROOT
from test_timed_summary import assert_same

BUS = str(ROOT / "tests" / "corpus" / "wizmodbus_bus.records")
RXTX = str(ROOT / "tests" / "corpus" / "wizmodbus_rxtx.records")


def _warnings(out: str) -> list[str]:
    return [line for line in out.splitlines() if line.startswith("vw3-decode: warning:")]


def test_glitch_bytes_in_a_frames_record_do_not_blame_the_line_speed(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _ = assert_same([BUS, "--stats", "--baud", "9600"], monkeypatch)
    assert out.splitlines()[0] == "88 frames, 88 noise bytes in 88 runs"
    assert _warnings(out) == []
    out, _ = assert_same([BUS, "--stats", "--json", "--baud", "9600"], monkeypatch)
    assert json.loads(out)["bus"]["overlaps"] == 0
    # The gaps themselves stay as the stamps give them (a negative gap is an adapter's burst stamp).
    assert json.loads(out)["bus"]["gaps_below_t35"] == 174


def test_a_wrong_line_speed_is_still_said_counting_frames_alone(monkeypatch: pytest.MonkeyPatch) -> None:
    expected = ["vw3-decode: warning: --baud 1200: 86 frames would overlap the one before at 1200 baud: "
                "the line is faster?"]
    for path in (BUS, RXTX):
        out, _ = assert_same([path, "--stats", "--baud", "1200"], monkeypatch)
        assert _warnings(out) == expected
