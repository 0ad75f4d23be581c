"""The plugin's quick lane for a request met before (lua/src/records.lua lane.request) keeps the length of the
answer it awaits, as the general path does (lua/src/stream.lua await_answer): a poll cut by the end of the
capture after one the quick lane took is the request reading, as vw3-decode says ('the capture ends inside a
request (4 of 8 bytes)'); before, the length was left aside there and the bytes were 'the response (4 of 37
bytes)', 0x20 read as a byte count. An answer cut after a quick-lane request stays one. Exact fields (tshark
-2) and every field as vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
POLL, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 0001 0002 0003")
WIDE, WIDE_ANSWER = rtu("0C 03 2000 000A"), rtu("0C 03 14" + "0001" * 10)
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.noise.reason"]


@pytest.mark.parametrize(
    ("last", "tail", "reason"),
    [(POLL, POLL[:4], "the capture ends inside a request (4 of 8 bytes)"),
     (WIDE, POLL[:4], "the capture ends inside a request (4 of 8 bytes)"),
     (POLL, ANSWER[:5], "the capture ends inside the response (5 of 11 bytes)")],
)
def test_after_a_request_the_quick_lane_took(tmp_path: Path, last: bytes, tail: bytes, reason: str) -> None:
    records = [POLL, ANSWER, WIDE, WIDE_ANSWER] * 4 + [last, tail]
    pcap = write_pcap(tmp_path / "polls.pcap", [(data, T0 + 0.1 * index) for index, data in enumerate(records)])
    got = run_tshark(pcap, *FIELDS)
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    assert got.stdout.splitlines()[-2:] == ["1;", f"4;{reason}"]
    differences = compare(python_items(pcap), lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])
