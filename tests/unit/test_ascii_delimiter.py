"""FC8 sub-function 03 (Change ASCII Input Delimiter) in Modbus ASCII: once the slave's answer echoes the
change, a line may end with CR and the character its data's high byte carries (here '!'); the frame keeps both
bytes (before: the frame was noise, "ASCII frame cut short by the next ':'"). A change back to LF ends that:
a later CR '!' line is a frame with a warning naming the byte in the LF's place (before: noise, which encoded
the defect; tests/unit/test_ascii_damaged_lf.py). vw3-decode's summary and --json, under the compiled engine and
VW3_PURE_PYTHON=1 (ASCII is framed in Python either way), whatever the chunks; the plugin:
tests/integration/test_lua_ascii_delimiter.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import ascii_items, run_cli, use_engine

from dissector.framing.ascii import AsciiFramer
from dissector.model import Chunk
from dissector.protocol.crc import lrc


def line(pdu: str) -> bytes:
    """`:` and the hex pairs of slave, PDU and LRC (no line end)."""
    binary = bytes.fromhex(pdu.replace(" ", ""))
    return b":" + (binary + bytes([lrc(binary)])).hex().upper().encode("ascii")


LINES = [
    line("01 03 0001 0001") + b"\r\n", line("01 03 02 0005") + b"\r\n",
    line("01 08 0003 2100") + b"\r\n", line("01 08 0003 2100") + b"\r\n",  # '!' (21h) from now on
    line("01 03 0001 0001") + b"\r!", line("01 03 02 0007") + b"\r!",
    line("01 03 0001 0001") + b"\r\n", line("01 03 02 0008") + b"\r\n",  # (LF still ends a line)
    line("01 08 0003 0A00") + b"\r\n", line("01 08 0003 0A00") + b"\r\n",  # back to LF
    line("01 03 0001 0001") + b"\r!", line("01 03 02 0009") + b"\r!",
]
DATA = b"".join(LINES)
NOT_LF = "line ends with CR then 21h where LF belongs (the spec ends a frame with CR LF)"
# (a request to slave 1 once '!' replaced its LF: the delimiter the slave takes in, Application Protocol 6.8.1;
# before, no warning; its answers may end either way)
NOT_SET = "line ends with CR then 0Ah where slave 1's delimiter 21h belongs (set by its answer to 08/03)"
SUMMARY = [
    "     1            -   1 request   Read Holding Registers 1  LRC ok",
    "     2            -   1 response  Read Holding Registers 1: 1=5 [#1]  LRC ok",
    "     3            -   1 request   Diagnostics 03h Change ASCII Input Delimiter = 8448 "
    "[new ASCII input delimiter: '!' (21h)]  LRC ok",
    "     4            -   1 response  Diagnostics 03h Change ASCII Input Delimiter = 8448 [#3]  LRC ok",
    "     5            -   1 request   Read Holding Registers 1  LRC ok",
    "     6            -   1 response  Read Holding Registers 1: 1=7 [#5]  LRC ok",
    f"     7            -   1 request   Read Holding Registers 1 [warning: {NOT_SET}]  LRC ok",
    "     8            -   1 response  Read Holding Registers 1: 1=8 [#7]  LRC ok",
    "     9            -   1 request   Diagnostics 03h Change ASCII Input Delimiter = 2560 "
    f"[new ASCII input delimiter: LF (0Ah)] [warning: {NOT_SET}]  LRC ok",
    "    10            -   1 response  Diagnostics 03h Change ASCII Input Delimiter = 2560 [#9]  LRC ok",
    f"    11            -   1 request   Read Holding Registers 1 [warning: {NOT_LF}]  LRC ok",
    f"    12            -   1 response  Read Holding Registers 1: 1=9 [#11] [warning: {NOT_LF}]  LRC ok",
]


@pytest.mark.parametrize("pure", [False, True])
def test_a_line_ends_with_the_delimiter_03_set(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "delimiter.txt"
    path.write_bytes(DATA)
    assert run_cli([str(path)]) == (0, "\n".join(SUMMARY) + "\n", "")
    items = [json.loads(row) for row in run_cli(["--json", str(path)])[1].splitlines()]
    assert [(item["kind"], bytes.fromhex(item["raw"])) for item in items] == [
        *[(kind, raw) for kind, raw in zip(["request", "response"] * 6, LINES)]]
    assert [item["warnings"] for item in items[6:]] == [[NOT_SET], [], [NOT_SET], [], [NOT_LF], [NOT_LF]]
    assert items[5]["registers"] == [{"address": 1, "value": 7}]


def test_the_same_whatever_the_chunks() -> None:
    whole = ascii_items(DATA)
    assert [kind for kind, _, _, _ in whole] == ["Frame"] * 12
    for size in (1, 2, 3, 16):
        assert ascii_items(DATA, size) == whole


def test_no_change_without_the_answer() -> None:
    # The request alone (no echo: the slave did not take it), or an exception to it: CR '!' is a damaged line end.
    for answer in (b"", line("01 88 01") + b"\r\n"):
        framer = AsciiFramer()
        out = framer.feed(Chunk(LINES[2] + answer + LINES[4] + LINES[5])) + framer.finish()
        assert [(type(item).__name__, item.raw, item.warnings) for item in out[-2:]] == [
            ("Frame", LINES[4], [NOT_LF]), ("Frame", LINES[5], [NOT_LF])]
