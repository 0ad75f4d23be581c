"""The plugin says what vw3-decode says of a normal answer whose every value is 16#8000 (ATV71: one at least is
real, since the drive answers exception 02 when every parameter is unreadable, p.38): each register ambiguous,
the note, no story; tests/unit/test_all_marked.py's frames under real tshark, one pass and two, every field
compared with vw3-decode --json (lua_compare), the RTU plugin and the Modbus/TCP names alike."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

REQUEST, ANSWER_P38, ALL_MARKED = "0C 03 20D0 0003", "0C 03 06 8000 0003 0002", "0C 03 06 8000 8000 8000"
NOTE = ("every value is 16#8000, but the VW3 A3 303 answers exception 02 when every parameter read is "
        "non-existent or protected: one at least is the value 32768")


def _pcap(tmp_path: Path) -> Path:
    frames = [REQUEST, ANSWER_P38, REQUEST, ALL_MARKED, "0C 03 0C8A 0002", "0C 03 04 8000 8000"]
    return write_pcap(tmp_path / "marked.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                 for index, frame in enumerate(frames)])


@pytest.mark.parametrize("two_pass", [True, False])
def test_each_value_is_ambiguous_and_the_frame_says_why(tmp_path: Path, two_pass: bool) -> None:
    pcap = _pcap(tmp_path)
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.reg.status", "-e", "vw3.note", "-Y", "vw3.kind == 2", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [
        "2|non-existent,ok,ok|",
        f"4|ambiguous,ambiguous,ambiguous|{NOTE}",
        f"6|ambiguous,ambiguous|{NOTE}",
    ]


def test_every_field_as_vw3_decode_says_it(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path)
    python = python_items(pcap, ["atv71"])
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71")
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
