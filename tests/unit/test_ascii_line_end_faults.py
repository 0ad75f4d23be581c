"""Modbus ASCII line ends a tolerant dissector shows as frames with a warning (framing/ascii.py), found by
hunt 55 (/tmp/hunt55/ascii_cronly*.txt, ascii_crcrlf.txt, ascii_delim*.txt):
- a line ended by CR without LF at the end of the capture is a frame, as one before the next ':' is (before:
  "16 bytes of noise", and an answer shown as "the capture ends inside the response (26 of 27 bytes)");
- CR CR LF (a tty's LF to CR LF on a line already ended by CR LF) is a frame with a warning (before: noise
  despite a good LRC, and its answer "[no request]");
- after 08/03 (Change ASCII Input Delimiter) set ';' for slave 2 (Application Protocol 6.8.1: it replaces LF
  at the end of the messages the slave takes in): a request to slave 2 ending CR LF is warned, a line of
  another slave ending CR ';' too; slave 2's answers may end either way (the spec names its input only), a
  broadcast with LF or any slave's character (before: every one of them without a warning).
Exact summary lines, under the engine and VW3_PURE_PYTHON=1 (ASCII is framed in Python either way), whatever
the chunks; the plugin: tests/integration/test_lua_ascii_line_end_faults.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.protocol.crc import lrc
from helpers import ascii_items, run_cli, use_engine


def line(pdu: str, end: bytes = b"\r\n") -> bytes:
    """`:`, the hex pairs of slave, PDU and LRC, then `end`."""
    binary = bytes.fromhex(pdu.replace(" ", ""))
    return b":" + (binary + bytes([lrc(binary)])).hex().upper().encode("ascii") + end


READ, ANSWER = "02 03 0C1E 0004", "02 03 08 0028 0258 01F4 0000"  # the card manual's 3102..3105 and its answer
SET = "02 08 0003 3B00"  # ';' (3Bh) in place of LF for slave 2
OTHER_READ, OTHER_ANSWER = "01 03 0C1E 0004", "01 03 08 0028 0258 01F4 0000"
BROADCAST = "00 06 2135 0005"  # (a write to every slave: no answer)
LOST_LF = "line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)"
AT_END = "line ends with CR without LF, at the end of the capture (the spec ends a frame with CR LF)"
TWO_CRS = "line ends with 2 CRs where the spec has one (a frame ends with CR LF)"
NOT_SET = "line ends with CR then 0Ah where slave 2's delimiter 3Bh belongs (set by its answer to 08/03)"
NOT_LF = "line ends with CR then 3Bh where LF belongs (the spec ends a frame with CR LF)"
HOLDING = "Read Holding Registers 3102..3105 (4)"
UNKNOWN = "the capture ends before any response: not known whether it was answered"
VALUES = f"{HOLDING}: 3102=40 3103=600 3104=500 3105=0"
CHANGE = "Diagnostics 03h Change ASCII Input Delimiter = 15104"
CHANGED = [
    f"     1            -   2 request   {CHANGE} [new ASCII input delimiter: ';' (3Bh)]  LRC ok",
    f"     2            -   2 response  {CHANGE} [#1]  LRC ok",
]

# (bytes, summary lines)
CASES = {
    "three lines ended by CR": (
        line(READ, b"\r") + line(ANSWER, b"\r") + line(READ, b"\r"),
        [f"     1            -   2 request   {HOLDING} [warning: {LOST_LF}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1] [warning: {LOST_LF}]  LRC ok",
         f"     3            -   2 request   {HOLDING} [{UNKNOWN}] [warning: {AT_END}]  LRC ok"],
    ),
    "the answer ended by CR at the end": (
        line(READ, b"\r") + line(ANSWER, b"\r"),
        [f"     1            -   2 request   {HOLDING} [warning: {LOST_LF}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1] [warning: {AT_END}]  LRC ok"],
    ),
    "CR CR LF": (
        line(READ, b"\r\r\n") + line(ANSWER),
        [f"     1            -   2 request   {HOLDING} [warning: {TWO_CRS}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1]  LRC ok"],
    ),
    "CR CR at the end": (
        line(READ) + line(ANSWER, b"\r\r"),
        [f"     1            -   2 request   {HOLDING}  LRC ok",
         f"     2            -   2 response  {VALUES} [#1] [warning: {AT_END}] [warning: {TWO_CRS}]  LRC ok"],
    ),
    "after 08/03, the delimiter set": (
        line(SET) + line(SET, b"\r;") + line(READ, b"\r;") + line(ANSWER, b"\r;"),
        [*CHANGED,
         f"     3            -   2 request   {HOLDING}  LRC ok",
         f"     4            -   2 response  {VALUES} [#3]  LRC ok"],
    ),
    "after 08/03, CR LF": (
        line(SET) + line(SET) + line(READ) + line(ANSWER),
        [*CHANGED,
         f"     3            -   2 request   {HOLDING} [warning: {NOT_SET}]  LRC ok",
         f"     4            -   2 response  {VALUES} [#3]  LRC ok"],
    ),
    "after 08/03, another slave": (
        line(SET) + line(SET) + line(OTHER_READ, b"\r;") + line(OTHER_ANSWER, b"\r;") + line(OTHER_READ),
        [*CHANGED,
         f"     3            -   1 request   {HOLDING} [warning: {NOT_LF}]  LRC ok",
         f"     4            -   1 response  {VALUES} [#3] [warning: {NOT_LF}]  LRC ok",
         f"     5            -   1 request   {HOLDING} [{UNKNOWN}]  LRC ok"],
    ),
    "after 08/03, a broadcast": (
        line(SET) + line(SET) + line(BROADCAST, b"\r;") + line(BROADCAST),
        [*CHANGED,
         "     3            -   0 request   Write Single Register 8501 = 5 [broadcast]  LRC ok",
         "     4            -   0 request   Write Single Register 8501 = 5 [broadcast]  LRC ok"],
    ),
}


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("case", list(CASES))
def test_summary(case: str, pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    data, lines = CASES[case]
    path = tmp_path / "capture.txt"
    path.write_bytes(data)
    assert run_cli([str(path)]) == (0, "\n".join(lines) + "\n", "")  # (the mode detected, as --mode ascii)


@pytest.mark.parametrize("case", list(CASES))
def test_the_same_whatever_the_chunks(case: str) -> None:
    data = CASES[case][0]
    whole = ascii_items(data)
    assert {kind for kind, _, _, _ in whole} == {"Frame"} and b"".join(raw for _, _, raw, _ in whole) == data
    for size in (1, 2, 3, 16):
        assert ascii_items(data, size) == whole
