"""FC8/03 (Change ASCII Input Delimiter) as pymodbus 3.16.1 does it (peer69: its ASCII client and server on a
pseudo-terminal, `client.diag_change_ascii_input_delimeter(delimiter=0x21, device_id=5)`, the bytes below as they
went over the line). Its client puts the character in the data word's low byte (0021, not the spec's 2100); its
server reads the high byte, as the spec has it, answers the echo and from then on ends every line, its echo
too, with CR and that byte: 00. The request is warned (the spec's server answers exception 03), but the echo is
the server's word that it took the change: its lines ending CR 00 are its new delimiter's, and the master's
that follow (pymodbus's client switched too) are what the slave takes in. Before, the low byte not 00 made the
echo teach nothing, and every line after it was warned `line ends with CR then 00h where LF belongs`. The
plugin: tests/integration/test_lua_pymodbus_delimiter_echo.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import ascii_items, run_cli, use_engine

LINES = [
    b":050300010002F5\r\n", b":05030400030006EB\r\n",
    b":050800030021CF\r\n", b":050800030021CF\r\x00",
    b":050300010002F5\r\x00", b":05030400030006EB\r\x00",
    b":050300020001F5\r\x00", b":0503020006F0\r\x00",
]
DATA = b"".join(LINES)
BAD_DATA = ("diagnostic data 0021 is not what sub-function 03h takes (a character, then 00): "
            "a server answers exception 03")
SUMMARY = [
    "     1            -   5 request   Read Holding Registers 1..2 (2)  LRC ok",
    "     2            -   5 response  Read Holding Registers 1..2 (2): 1=3 2=6 [#1]  LRC ok",
    "     3            -   5 request   Diagnostics 03h Change ASCII Input Delimiter = 33 "
    f"[warning: {BAD_DATA}]  LRC ok",
    "     4            -   5 response  Diagnostics 03h Change ASCII Input Delimiter = 33 [#3]  LRC ok",
    "     5            -   5 request   Read Holding Registers 1..2 (2)  LRC ok",
    "     6            -   5 response  Read Holding Registers 1..2 (2): 1=3 2=6 [#5]  LRC ok",
    "     7            -   5 request   Read Holding Registers 2  LRC ok",
    "     8            -   5 response  Read Holding Registers 2: 2=6 [#7]  LRC ok",
]


@pytest.mark.parametrize("pure", [False, True])
def test_pymodbus_delimiter_change_is_followed(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "pymodbus_delimiter.bin"
    path.write_bytes(DATA)
    assert run_cli(["-n", str(path)]) == (0, "\n".join(SUMMARY) + "\n", "")


def test_the_same_whatever_the_chunks() -> None:
    whole = ascii_items(DATA)
    assert [(kind, raw) for kind, _, raw, *_ in whole] == [("Frame", line) for line in LINES]
    for size in (1, 2, 3, 16):
        assert ascii_items(DATA, size) == whole
