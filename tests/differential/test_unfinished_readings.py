"""A reading whose bytes have not all come is not waited for across a record that is a frame of its own (framing/
reach.py _crosses_framed_record, in _valid_frame_at and _match; the engine's crosses_framed_record in _summary.c,
valid_frame_at and _timedframe.h decide_at): the engine and the Python stages (VW3_PURE_PYTHON=1) show the same
lines, exactly. In step, the answer awaited whose byte count reads 17 bytes, cut by a request's record and
completed by the record after it with a CRC that checks over the three: the Python stages do not wait for it
(49f5224: noise, a damaged FC12 request, the request, noise); the engine waited and took one 17-byte answer.
And the framer's 'does a frame start here' past a damaged request ('0c 01 be 11': an answer of 195 bytes; '0c 17
00 01': an FC23 request whose byte count has not come)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import same_lines_of_records as _lines

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
FC8 = bytes.fromhex("0c0800001234bb74")  # (its CRC register back at its start: it and a frame check as one)
DAMAGED = REQUEST[:-1] + bytes([REQUEST[-1] ^ 1])
HEAD = bytes.fromhex("0c030c0001")  # (the answer awaited's first 5 bytes: byte count 12, 17 bytes)
TAIL = rtu((HEAD + REQUEST + bytes.fromhex("0002")).hex())[-4:]  # (its CRC checks over the three records)
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
VALUES = "8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)"
RAW_VALUES = "8400=32768 8401=3 8402=2"  # (no read before names the device)
CHARACTER = 11 / 19200


def test_the_answer_awaited_is_not_waited_for_across_a_request_s_record(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # (back to back: no silence inside the 17 bytes, which the engine would hand over)
    records = [(REQUEST, 0.0), (HEAD, 0.01), (REQUEST, 0.01 + 5 * CHARACTER), (TAIL, 0.01 + 13 * CHARACTER),
               (REQUEST, 2.0), (ANSWER, 2.01)]
    assert _lines(tmp_path, records, monkeypatch) == [
        "     1  0.000000000  12 request   Read Holding Registers 8400..8402 (3) [no response]  CRC ok",
        "     2  0.010000000   - noise     1 byte of noise at offset 8: 0c",
        "     3  0.010000000   3 request   Get Comm Event Log [no response]  "
        "CRC BAD (received 0x0100, expected 0x4501)",
        "     4  0.012864583  12 request   Read Holding Registers 8400..8402 (3) [no response]  CRC ok",
        f"     5  0.017447917   - noise     4 bytes of noise at offset 21: 00 02 {TAIL[2]:02x} {TAIL[3]:02x}",
        f"     6  2.000000000  {READ}",
        f"     7  2.010000000  12 response  Read Holding Registers 8400..8402 (3): {RAW_VALUES} [#6, 10.0 ms]"
        "  CRC ok",
    ]


@pytest.mark.parametrize("then", ["0c01be11", "0c170001"], ids=["long", "need"])
def test_what_follows_a_damaged_request_is_settled_by_the_next_record(
    then: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (DAMAGED + bytes.fromhex(then), 2.0), (REQUEST, 3.0), (ANSWER, 3.01)]
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#1, 10.0 ms]  CRC ok",
        "     3  2.000000000   - noise     12 bytes of noise at offset 19: 0c 03 20 d0 00 03 0e ee "
        + " ".join(then[k:k + 2] for k in range(0, 8, 2)),
        f"     4  3.000000000  {READ}",
        f"     5  3.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#4, 10.0 ms]  CRC ok",
    ]


def test_an_fc8_scan_stops_at_a_record_that_is_a_scanned_frame(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # (a record of a code without a length rule whose CRC checks at its end is a frame of its own: _ends_record;
    # the engine's ends_record alike. Before, the FC8/00 scan, which the engine frames itself in step, read both
    # records as one Return Query Data of 16 bytes, its CRC checking over both)
    user = rtu("0C 46 0102 0304")
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (FC8, 2.0), (user, 2.0 + 8 * CHARACTER), (REQUEST, 3.0),
               (ANSWER, 3.01)]
    assert _lines(tmp_path, records, monkeypatch) == [
        f"     1  0.000000000  {READ}",
        f"     2  0.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#1, 10.0 ms]  CRC ok",
        "     3  2.000000000   - noise     8 bytes of noise at offset 19: 0c 08 00 00 12 34 bb 74",
        "     4  2.004583333  12 request   User-defined function 70 4 bytes of data [no response] "
        "[warning: User-defined function 70 (70) is not supported by the VW3 A3 303]  CRC ok",
        f"     5  3.000000000  {READ}",
        f"     6  3.010000000  12 response  Read Holding Registers 8400..8402 (3): {VALUES} [#5, 10.0 ms]  CRC ok",
    ]
