"""The plugin cuts a noise run at a silence of t3.5 before a record (lua/src/stream.lua add_noise,
flush_noise; feed.lua consume keeps the record before one the framer stops at), as vw3-decode does
(framing/stream.py): noise records a second apart were one item of all their bytes, shown in the last record
('(3 bytes continue in #10)' in the others); now each is its own. The plugin has no line speed setting: its
t3.5 is 19200 baud's, the Python framers' without --baud. Exact Info with -2 (one pass shows 'noise (2 bytes so
far)' until a frame or the end: the run is one for the framer's decisions), every field as vw3-decode
says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
NOISE = bytes.fromhex("ff00aa")
REQUEST = rtu("0C 03 20D0 0003")


def _check(tmp_path: Path, records: list[tuple[bytes, float]], infos: list[str]) -> None:
    pcap = write_pcap(tmp_path / "noise.pcap", [(data, 1700000000 + time) for data, time in records])
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=True)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    assert got.stdout.splitlines() == infos
    two, _, _ = lua_items(pcap)
    differences = compare(python_items(pcap), two)
    assert not differences, "\n".join(differences[:40])


def test_noise_records_a_second_apart(tmp_path: Path) -> None:
    _check(tmp_path, [(NOISE, 0.0), (NOISE, 1.0), (NOISE, 2.0)], ["noise (3 bytes)"] * 3)


def test_noise_without_a_silence_stays_one_run(tmp_path: Path) -> None:
    # (2 ms apart: 0.28 ms of silence after 3 characters at 19200 baud, below t3.5)
    records = [(NOISE, 0.0), (NOISE, 0.002), (NOISE + REQUEST, 3.0), (NOISE, 4.0)]
    _check(tmp_path, records, ["(3 bytes of noise in #2)", "noise (6 bytes)",
                               "noise (3 bytes); 12 Read Holding Registers request 8400..8402 (3)", "noise (3 bytes)"])


def test_a_silence_before_the_record_the_framer_stopped_at(tmp_path: Path) -> None:
    # 'fe' is noise only once the 37 bytes '0c 03 20' would need are in (byte count 32), and the framer stops
    # at the second record's start: feed.lua consume kept that record's time alone, not the first's, from
    # which the silence before it is measured ('fe' and '0c 03 20' were one run of 4 bytes).
    records = [(b"\xfe", 0.0), (bytes.fromhex("0c0320") + rtu("0C 83 02"), 1.0),
               *((bytes(16), 1.01 + k / 100) for k in range(3))]
    _check(tmp_path, records, ["noise (1 byte)",
                               "noise (3 bytes); 12 Read Holding Registers exception 2 (Illegal Data Address)",
                               "(16 bytes of noise in #5)", "(16 bytes of noise in #5)", "noise (48 bytes)"])
