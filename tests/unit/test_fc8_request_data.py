"""FC8 Diagnostics: what a request's data word means for its sub-function (Application Protocol 6.8.1,
data/modbus.toml [diagnostic_data]): 01 with FF00 also clears the communications event log, 03 sets the ASCII
input delimiter to the character in its high byte (shown), the counters (0Bh..12h) and the others listed take
0000; a word the spec does not allow draws a warning (a server answers exception 03). Before: plain numbers,
no note, no warning. Exact outputs for exact bytes, under the engine (which hands these requests to the Python
stages, _tables.h diagnostic_quiet) and VW3_PURE_PYTHON=1; the plugin: tests/integration/
test_lua_fc8_request_data.py."""
from __future__ import annotations

import io
import json
import re

import pytest

from dissector.app.cli import Environment, run
from helpers import rtu, use_engine

FRAMES = [
    rtu("01 08 0001 FF00"), rtu("01 08 0001 FF00"),  # restart, clearing the event log
    rtu("01 08 0001 0000"), rtu("01 08 0001 0000"),  # restart, keeping it: nothing to say
    rtu("01 08 0003 3B00"), rtu("01 08 0003 3B00"),  # delimiter ';'
    rtu("01 08 0003 0A00"), rtu("01 08 0003 0A00"),  # delimiter LF, by its name
    rtu("01 08 0003 0100"), rtu("01 08 0003 0100"),  # an unprintable one, in hex
    rtu("01 08 000B 0001"), rtu("01 88 03"),  # a counter asked with data 0001: refused
    rtu("01 08 000B 0000"), rtu("01 08 000B 0007"),  # as the spec has it
    rtu("01 08 0003 3B01"), rtu("01 88 03"),
    rtu("01 08 0001 1234"), rtu("01 88 03"),
    rtu("01 08 0000 1234"), rtu("01 08 0000 1234"),  # Return Query Data: any data
    rtu("01 03 0000 0001"), rtu("01 03 02 0005"),
]
RESTART, DELIMITER, COUNT = (
    "Diagnostics 01h Restart Communications Option", "Diagnostics 03h Change ASCII Input Delimiter",
    "Diagnostics 0Bh Return Bus Message Count")
REFUSED = "Diagnostics: exception 3 (Illegal Data Value)"


def refused(data: str, subfunction: str, allowed: str) -> str:
    return f"[warning: diagnostic data {data} is not what sub-function {subfunction} takes ({allowed}): " \
           "a server answers exception 03]"


def decode(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    out, err = io.StringIO(), io.StringIO()
    assert run([*options, "-n", "-"], Environment(io.BytesIO(data), out, err, False, False)) == 0
    assert err.getvalue() == ""
    return out.getvalue()


def both(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch) -> str:
    engine, pure = decode(data, options, monkeypatch, False), decode(data, options, monkeypatch, True)
    assert engine == pure
    return engine


def test_summary(monkeypatch: pytest.MonkeyPatch) -> None:
    lines = [re.sub(r"\s+", " ", line.strip()) for line in both(b"".join(FRAMES), [], monkeypatch).splitlines()]
    assert lines == [
        f"1 - 1 request {RESTART} = 65280 [clear the communications event log] CRC ok",
        f"2 - 1 response {RESTART} = 65280 [#1] CRC ok",
        f"3 - 1 request {RESTART} = 0 CRC ok",
        f"4 - 1 response {RESTART} = 0 [#3] CRC ok",
        f"5 - 1 request {DELIMITER} = 15104 [new ASCII input delimiter: ';' (3Bh)] CRC ok",
        f"6 - 1 response {DELIMITER} = 15104 [#5] CRC ok",
        f"7 - 1 request {DELIMITER} = 2560 [new ASCII input delimiter: LF (0Ah)] CRC ok",
        f"8 - 1 response {DELIMITER} = 2560 [#7] CRC ok",
        f"9 - 1 request {DELIMITER} = 256 [new ASCII input delimiter: 01h] CRC ok",
        f"10 - 1 response {DELIMITER} = 256 [#9] CRC ok",
        f"11 - 1 request {COUNT} = 1 {refused('0001', '0Bh', '0000')} CRC ok",
        f"12 - 1 exception {REFUSED} [#11] CRC ok",
        f"13 - 1 request {COUNT} = 0 CRC ok",
        f"14 - 1 response {COUNT} = 7 [#13] CRC ok",
        f"15 - 1 request {DELIMITER} = 15105 {refused('3B01', '03h', 'a character, then 00')} CRC ok",
        f"16 - 1 exception {REFUSED} [#15] CRC ok",
        f"17 - 1 request {RESTART} = 4660 {refused('1234', '01h', '0000 or FF00')} CRC ok",
        f"18 - 1 exception {REFUSED} [#17] CRC ok",
        "19 - 1 request Diagnostics 00h Return Query Data = 4660 CRC ok",
        "20 - 1 response Diagnostics 00h Return Query Data = 4660 [#19] CRC ok",
        "21 - 1 request Read Holding Registers 0 CRC ok",
        "22 - 1 response Read Holding Registers 0: 0=5 [#21] CRC ok",
    ]


@pytest.mark.parametrize("subfunction", [0x02, 0x04, 0x0A, 0x0C, 0x0D, 0x0E, 0x0F, 0x10, 0x11, 0x12, 0x14])
def test_the_others_take_0000(subfunction: int, monkeypatch: pytest.MonkeyPatch) -> None:
    def warnings(data: str) -> list[str]:
        [line] = both(rtu(f"07 08 00{subfunction:02X} {data}"), ["--json"], monkeypatch).splitlines()
        return json.loads(line)["warnings"]

    assert warnings("0000") == []
    assert warnings("FFFF") == [
        f"diagnostic data FFFF is not what sub-function {subfunction:02X}h takes (0000): a server answers exception 03"]


def test_detail_and_json(monkeypatch: pytest.MonkeyPatch) -> None:
    data = rtu("01 08 0001 FF00") + rtu("01 08 0001 FF00")
    assert both(data, ["-V"], monkeypatch).split("\n\n")[0].splitlines() == [
        "Frame 1: 8 bytes at offset 0, request (RTU)",
        "    Modbus RTU",
        "        Slave: 1",
        "        Function: 8 (0x08) Diagnostics",
        "        Sub-function: Restart Communications Option (1)",
        "        Data: ff00",
        "        Sub-function name: Restart Communications Option",
        "        CRC: 0x3BF0 [CRC ok]",
        "    Response in frame: 2",
        "    Note: clear the communications event log",
    ]
    request, answer = (json.loads(line) for line in both(rtu("01 08 0003 3B00") * 2, ["--json"], monkeypatch).splitlines())
    assert (request["notes"], request["warnings"], answer["notes"]) == (["new ASCII input delimiter: ';' (3Bh)"], [], [])
