"""A bit read's answer (FC1, FC2) with byte count 0 says its count as a register read's does: without its
request `Read Coils (0)`, as `Read Holding Registers (0)` (no byte, no bit: a quantity of 0, data/modbus.toml
[lift.read_bits_response] unpaired_unit 0), with -V's `[Quantity: 0]` and --json's `"quantity": 0`; with its
request the window asked and the warning, as FC3's. Under the compiled engine and VW3_PURE_PYTHON=1 (the
plugin's side: tests/integration/test_lua_bit_read_of_none.py)."""
from __future__ import annotations

import json

import pytest

from helpers import rtu, run_cli, use_engine

NO_REQUEST = " [no request] [response without a matching request in the capture]  CRC ok\n"
HEAD = "     1            -   1 response  "


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("frame", "info"), [
    ("01 01 00", "Read Coils (0)"),
    ("01 02 00", "Read Discrete Inputs (0)"),
    ("01 03 00", "Read Holding Registers (0)"),
    ("01 01 01 05", "Read Coils: 10100000"),  # (a byte holds 1 to 8 bits: no count)
])
def test_summary_without_request(frame: str, info: str, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--hex", rtu(frame).hex()])
    assert (status, err) == (0, "")
    assert out == f"{HEAD}{info}{NO_REQUEST}"


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("function", [1, 2])
def test_detail_and_json_without_request(function: int, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    frame = rtu(f"01 {function:02X} 00").hex()
    status, out, _ = run_cli(["-V", "--hex", frame])
    assert status == 0
    lines = out.splitlines()
    assert lines[4:7] == ["        [Quantity: 0]", "        Byte count: 0 (0x0)", "        Bits (0)"]
    status, out, _ = run_cli(["--json", "--hex", frame])
    record = json.loads(out)
    assert (record["quantity"], record["bits"], record["fields"]["byte_count"]) == (0, [], 0)
    assert "start" not in record


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("function", "name", "what"), [(1, "Read Coils", "bits"),
                                                       (2, "Read Discrete Inputs", "bits"),
                                                       (3, "Read Holding Registers", "registers")])
def test_with_its_request(function: int, name: str, what: str, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    request, answer = rtu(f"01 {function:02X} 0000 0008").hex(), rtu(f"01 {function:02X} 00").hex()
    status, out, _ = run_cli(["--hex", request, "--hex", answer])
    assert status == 0
    assert out.splitlines()[1] == (f"     2            -   1 response  {name} 0..7 (8) [#1] [warning: byte count 0 "
                                   f"disagrees with the {what} asked (8)]  CRC ok")
    status, out, _ = run_cli(["--json", "--hex", request, "--hex", answer])
    record = json.loads(out.splitlines()[1])
    assert (record["start"], record["quantity"], record["request_frame"]) == (0, 8, 1)
