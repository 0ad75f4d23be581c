"""The plugin as vw3-decode on a request cut short (framing/rtu.py _counts_nothing, lua/src/rtu.lua
counts_nothing): '01 03 00 00 00', a record of a request's first bytes, was an answer with byte count 0 and a bad
CRC ('Read Holding Registers response 0 [...] BAD CRC'). A reading with a bad CRC whose byte count is 0 is none:
the record is noise. (tshark stops before a record the capture ends inside: vw3-decode's reason for one, 'the
capture ends inside a request', is tests/differential/test_cut_requests.py's.) Exact Info (tshark -2) and every
field as vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

ONE, ONE_ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")
READ_ONE, ONE_ANSWERED = "1 Read Holding Registers request 0", "1 Read Holding Registers response 0"


def test_a_record_of_a_request_s_first_bytes(tmp_path: Path) -> None:
    records = [(ONE, 0.0), (ONE[:5], 1.0), (ONE, 2.0), (ONE_ANSWER, 2.01)]
    pcap = write_pcap(tmp_path / "short.pcap", [(data, 1700000000 + time) for data, time in records])
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info")
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    assert got.stdout.splitlines() == [READ_ONE, "noise (5 bytes)", READ_ONE, ONE_ANSWERED]
    python = python_items(pcap)
    assert python[1].data["reason"] == "a silence cuts a request (5 of 8 bytes)"  # (as live: test_silence_cut.py)
    differences = compare(python, lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])
