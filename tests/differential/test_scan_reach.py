"""A CRC scan does not reach across a record that is a frame of its own (framing/reach.py _framed_reach; the
engine's framed_reach in _summary.c): the engine and the Python stages (VW3_PURE_PYTHON=1) show the same lines,
exactly. A damaged FC8/00 Return Query Data (a CRC scan, which the engine frames itself in step) whose CRC over it
and the next record, an intact request, checks by chance was read as one 16-byte frame: 'Return Query Data data
1234bb740c0320d00003' and the request lost (its echo taken for the answer). A user-defined code (the Python
stages' scan) alike: damaged_stream(3051) written with -w read back a noise run and the FC43 request after it as
'User-defined function 70' (tests/integration/test_written_records.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.protocol.crc import crc16
from helpers import rtu
from test_timed_summary import same_lines_of_records as _lines

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
# (the last two bytes chosen so that the record and the request after it check as one frame)
FC8 = bytes.fromhex("0c0800001234bb74")
USER = bytes.fromhex("2946a54dca182530bb1d6d132cded6237b2ed91e3f72480b")  # (user-defined code 70, slave 41)
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
VALUES = "8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)"
CHARACTER = 11 / 19200  # (the request follows the record's last byte at once: no silence inside)


def _crossing(first: bytes) -> list[tuple[bytes, float]]:
    """A read, then `first` and the request right after it (no silence inside), which check as one frame."""
    whole = first + REQUEST
    assert crc16(whole[:-2]) == whole[-2] | whole[-1] << 8
    return [(REQUEST, 0.0), (ANSWER, 0.01), (first, 2.0), (REQUEST, 2.0 + len(first) * CHARACTER)]


def test_an_fc8_scan_stops_at_a_record_that_is_a_frame(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (then the 16 bytes again in one record, the echo of the reading across: the engine wrote both lines itself)
    records = [*_crossing(FC8), (FC8 + REQUEST, 2.03), (REQUEST, 3.0), (ANSWER, 3.01)]
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#1, 10.0 ms]  CRC ok",
        "     3  2.000000000   - noise     8 bytes of noise at offset 19: 0c 08 00 00 12 34 bb 74",
        f"     4  2.004583333  {READ[:-8]} [no response]  CRC ok",
        "     5  2.030000000  12 request   Diagnostics 00h Return Query Data data 1234bb740c0320d00003"
        " [no response]  CRC ok",
        f"     6  3.000000000  {READ}",
        f"     7  3.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#6, 10.0 ms]  CRC ok",
    ]


def test_a_user_defined_scan_stops_at_a_record_that_is_a_frame(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    assert _lines(tmp_path, [*_crossing(USER), (ANSWER, 2.03)], monkeypatch) == [
        f"     1  0.000000000  {READ}",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#1, 10.0 ms]  CRC ok",
        "     3  2.000000000   - noise     24 bytes of noise at offset 19: "
        "29 46 a5 4d ca 18 25 30 bb 1d 6d 13 2c de d6 23…",
        f"     4  2.013750000  {READ}",
        f"     5  2.030000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#4, 16.2 ms]  CRC ok",
    ]
