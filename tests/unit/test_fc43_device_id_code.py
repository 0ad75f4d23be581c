"""FC43/14 Read Device Identification: a request whose Read Device ID code is not one of the spec's 01..04
(data/modbus.toml [limits] device_id_code, the codes [device_id_codes] names) is warned about: a server
answers it with exception 03 (Application Protocol 6.21). Before: no warning. Exact outputs for exact bytes,
under the engine and VW3_PURE_PYTHON=1; the plugin: tests/integration/test_lua_fc43_device_id_code.py."""
from __future__ import annotations

import io
import json
import re

import pytest

from dissector.app.cli import Environment, run
from dissector.protocol.spec import SPEC
from helpers import rtu, use_engine

WARNING = "read device id code 5 outside the spec's 1..4 (a server answers exception 03)"
FC43 = "Encapsulated Interface Transport"
BAD, REFUSED = rtu("01 2B 0E 05 00"), rtu("01 AB 03")
BASIC, ANSWER = rtu("01 2B 0E 01 00"), rtu("01 2B 0E 01 01 00 00 01 00 03 41 42 43")
CAPTURE = BAD + REFUSED + BASIC + ANSWER + BAD


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


def test_the_limit_is_the_codes_the_spec_names() -> None:
    low, high = SPEC.limits["device_id_code"]  # type: ignore[misc]
    assert sorted(SPEC.device_id_codes) == list(range(low, high + 1)) == [1, 2, 3, 4]


def test_summary(monkeypatch: pytest.MonkeyPatch) -> None:
    assert [re.sub(r"\s+", " ", line.strip()) for line in both(CAPTURE, [], monkeypatch).splitlines()] == [
        f"1 - 1 request {FC43} Read Device Identification, 5, from object 0 [warning: {WARNING}] CRC ok",
        f"2 - 1 exception {FC43}: exception 3 (Illegal Data Value) [#1] CRC ok",
        f"3 - 1 request {FC43} Read Device Identification, basic, from object 0 CRC ok",
        f"4 - 1 response {FC43} Read Device Identification, basic: VendorName='ABC' [#3] CRC ok",
        f"5 - 1 request {FC43} Read Device Identification, 5, from object 0 "
        f"[the capture ends before any response: not known whether it was answered] [warning: {WARNING}] CRC ok",
    ]


@pytest.mark.parametrize("code", [0x00, 0x01, 0x04, 0x05, 0xFF])
def test_each_code(code: int, monkeypatch: pytest.MonkeyPatch) -> None:
    [line] = both(rtu(f"07 2B 0E {code:02X} 00"), ["--json"], monkeypatch).splitlines()
    expected = [] if 1 <= code <= 4 else [f"read device id code {code} outside the spec's 1..4 (a server answers exception 03)"]
    assert json.loads(line)["warnings"] == expected


def test_other_mei_types_are_not_checked(monkeypatch: pytest.MonkeyPatch) -> None:
    # MEI 13 (CANopen) has no Read Device ID code: its bytes are its own
    [line] = both(rtu("07 2B 0D 05 00"), ["--json"], monkeypatch).splitlines()
    assert json.loads(line)["warnings"] == []


def test_detail(monkeypatch: pytest.MonkeyPatch) -> None:
    assert both(BAD + REFUSED, ["-V"], monkeypatch).split("\n\n")[0].splitlines() == [
        "Frame 1: 7 bytes at offset 0, request (RTU)",
        "    Modbus RTU",
        "        Slave: 1",
        f"        Function: 43 (0x2B) {FC43}",
        "        MEI type: Read Device Identification (14)",
        "        Body",
        "            Read code: Unknown (5)",
        "            Object id: 0 (0x0)",
        "        CRC: 0xB772 [CRC ok]",
        "    Response in frame: 2",
        f"    Warning: {WARNING}",
    ]
