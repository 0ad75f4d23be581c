"""A response from slave 0: no server answers a broadcast (Application Protocol 4.1: "no response is returned
to broadcast requests") and a server answers with its own address. Such a frame answers nothing (the broadcast
keeps its [broadcast], it awaits no answer) and is warned about, naming the broadcast it follows when it is of
its function; before: only the note "response without a matching request in the capture", though the
broadcast is in the capture. A frame with a broadcast's own bytes (FC5, FC6, FC8: an answer's shape too) is a
broadcast again. Exact outputs for exact bytes, under the engine and VW3_PURE_PYTHON=1; the plugin:
tests/integration/test_lua_broadcast_answer.py."""
from __future__ import annotations

import io
import json
import re

import pytest

from dissector.app.cli import Environment, run
from helpers import rtu, use_engine

WRITE = rtu("00 10 2329 0001 02 000A")  # Write Multiple Registers 9001 = 10, broadcast
WRITTEN = rtu("00 10 2329 0001")  # its answer's shape, from slave 0
REFUSED = rtu("00 90 02")
AFTER = "response from slave 0 after broadcast #1: no server answers a broadcast"
ADDRESS = "response from slave 0, the broadcast address: a server answers with its own address"
UNMATCHED = "response without a matching request in the capture"


def decode(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    out, err = io.StringIO(), io.StringIO()
    assert run([*options, "-n", "-"], Environment(io.BytesIO(data), out, err, False, False)) == 0
    assert err.getvalue() == ""
    return out.getvalue()


def both(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch) -> list[str]:
    engine, pure = decode(data, options, monkeypatch, False), decode(data, options, monkeypatch, True)
    assert engine == pure
    return [re.sub(r"\s+", " ", line.strip()) for line in engine.splitlines()]


CASES = {
    "answer to a broadcast": (
        WRITE + WRITTEN + rtu("01 03 0000 0001") + rtu("01 03 02 0005"),
        ["1 - 0 request Write Multiple Registers 9001: 9001=10 [broadcast] CRC ok",
         f"2 - 0 response Write Multiple Registers 9001 written [warning: {AFTER}] CRC ok",
         "3 - 1 request Read Holding Registers 0 CRC ok",
         "4 - 1 response Read Holding Registers 0: 0=5 [#3] CRC ok"],
    ),
    "exception to a broadcast": (
        WRITE + REFUSED,
        ["1 - 0 request Write Multiple Registers 9001: 9001=10 [broadcast] CRC ok",
         f"2 - 0 exception Write Multiple Registers: exception 2 (Illegal Data Address) [warning: {AFTER}] "
         "CRC ok"],
    ),
    "two answers to a broadcast": (
        WRITE + WRITTEN + WRITTEN,
        ["1 - 0 request Write Multiple Registers 9001: 9001=10 [broadcast] CRC ok",
         f"2 - 0 response Write Multiple Registers 9001 written [warning: {AFTER}] CRC ok",
         f"3 - 0 response Write Multiple Registers 9001 written [warning: {AFTER}] CRC ok"],
    ),
    "slave 0 answering with no broadcast before": (
        rtu("01 03 0000 0001") + rtu("01 03 02 0005") + WRITTEN,
        ["1 - 1 request Read Holding Registers 0 CRC ok",
         "2 - 1 response Read Holding Registers 0: 0=5 [#1] CRC ok",
         f"3 - 0 response Write Multiple Registers 9001 written [no request] [{UNMATCHED}] [warning: {ADDRESS}] CRC ok"],
    ),
    "slave 0 answering another function": (
        WRITE + rtu("00 03 02 000A"),
        ["1 - 0 request Write Multiple Registers 9001: 9001=10 [broadcast] CRC ok",
         f"2 - 0 response Read Holding Registers (1): ?+0=10 [no request] [{UNMATCHED}] [warning: {ADDRESS}] CRC ok"],
    ),
    "a broadcast's own bytes again": (
        rtu("00 06 2329 000A") * 2,
        ["1 - 0 request Write Single Register 9001 = 10 [broadcast] CRC ok",
         "2 - 0 request Write Single Register 9001 = 10 [broadcast] CRC ok"],
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_summary(case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    data, expected = CASES[case]
    assert both(data, [], monkeypatch) == expected


def test_json_and_detail(monkeypatch: pytest.MonkeyPatch) -> None:
    request, answer = (json.loads(line) for line in both(WRITE + WRITTEN, ["--json"], monkeypatch))
    assert (request["broadcast"], request.get("response_frame"), request["warnings"], request["notes"]) == (
        True, None, [], [])
    assert (answer["kind"], answer["slave"], answer.get("request_frame"), answer["warnings"], answer["notes"]) == (
        "response", 0, None, [AFTER], [])
    tree = both(WRITE + WRITTEN, ["-V"], monkeypatch)
    assert tree[tree.index("Frame 2: 8 bytes at offset 11, response (RTU)"):] == [
        "Frame 2: 8 bytes at offset 11, response (RTU)",
        "Modbus RTU",
        "Slave: 0",
        "Function: 16 (0x10) Write Multiple Registers",
        "Start address: 9001 (0x2329)",
        "Quantity: 1 (0x1)",
        "CRC: 0x" + WRITTEN[-1:].hex().upper() + WRITTEN[-2:-1].hex().upper() + " [CRC ok]",
        f"Warning: {AFTER}",
        "",
    ]
