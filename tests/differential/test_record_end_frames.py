"""A record's end settles a frame (framing/rtu.py _scan, _match; _summary.c scan_length): the engine and the
Python stages (VW3_PURE_PYTHON=1) show the same lines, exactly, for pcaps whose records are frames: an FC8/00
Return Query Data (a CRC scan) whose record ends where its CRC checks, though a CRC over it and the next
record's first bytes checks too (the engine took that longer reading where the Python stages took the
record's: '... data 1234ec61ffff' against '= 4660' and 4 bytes of noise), and answers with a bad CRC."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import same_lines_of_records as _lines

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
BAD = ANSWER[:-1] + bytes([ANSWER[-1] ^ 1])
FC8 = rtu("0C 08 0000 1234")
LONGER = rtu((FC8 + b"\xff\xff").hex())  # (a CRC scan from the FC8 frame's start checks 12 bytes too)
READ = "12 request   Read Holding Registers 8400..8402 (3)"
VALUES = "8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)"
RAW = "8400=32768 8401=3 8402=2"  # (two good answers only: no profile chosen for slave 12)


def test_a_scanned_frame_ends_with_its_record(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (FC8, 2.0), (LONGER[8:] + REQUEST, 2.0), (ANSWER, 2.06)]
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}  CRC ok",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#1, 10.0 ms]  CRC ok",
        "     3  2.000000000  12 request   Diagnostics 00h Return Query Data = 4660 [no response]  CRC ok",
        "     4  2.000000000   - noise     4 bytes of noise at offset 27: ff ff 01 b0",
        f"     5  2.000000000  {READ}  CRC ok",
        f"     6  2.060000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#5, 60.0 ms]  CRC ok",
    ]


@pytest.mark.parametrize("together", [False, True])
def test_an_answer_with_a_bad_crc(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, together: bool) -> None:
    first = [(REQUEST + BAD, 0.0)] if together else [(REQUEST, 0.0), (BAD, 0.01)]
    records = [*first, (REQUEST, 2.0), (ANSWER, 2.01)]
    bad = f"{RAW} [#1, 0.0 ms]" if together else f"{RAW} [#1, 10.0 ms]"
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}  CRC ok",
        f"     2  {'0.000000000' if together else '0.010000000'}  12 response  Read Holding Registers 8400..8402 (3): {bad}"
        "  CRC BAD (received 0xE517, expected 0xE417)",
        f"     3  2.000000000  {READ}  CRC ok",
        f"     4  2.010000000  12 response  Read Holding Registers 8400..8402 (3): {RAW} [#3, 10.0 ms]  CRC ok",
    ]


def test_a_record_that_is_a_damaged_frame_after_the_engine_s_frames(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The engine hands the stream over at the record's start (a bad CRC is the Python stages'): that a record
    # starts there is kept (stream.py _record_starts_at), so the record is a damaged answer both ways (a record
    # that is a frame), not '0c 03 04' of noise before a request whose CRC checks across the record's end.
    request = rtu("0C 03 0000 0001")
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (bytes.fromhex("0C0304") + request[:6], 1.0),
               (request[6:] + ANSWER, 1.01)]
    alone = "[no request] [response without a matching request in the capture]"
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}  CRC ok",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {RAW} [#1, 10.0 ms]  CRC ok",
        f"     3  1.000000000  12 response  Read Holding Registers (2): ?+0=3075 ?+1=0 {alone}"
        "  CRC BAD (received 0x0100, expected 0xA3D5)",
        "     4  1.010000000   - noise     2 bytes of noise at offset 28: 85 17",
        f"     5  1.010000000  12 response  Read Holding Registers (3): ?+0=32768 ?+1=3 ?+2=2 {alone}  CRC ok",
    ]
