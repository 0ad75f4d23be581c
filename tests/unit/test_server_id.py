"""Report Server ID (FC17) in vw3-decode: -V, --json and the summary line, for libmodbus's answer."""
from __future__ import annotations

import json

from helpers import rtu, run_cli
from server_id import REQUEST, RESPONSE, check_decoded


def test_libmodbus_answer_in_vw3_decode() -> None:
    check_decoded(REQUEST, RESPONSE, "LMB3.1.6")


def test_odd_run_indicator_and_binary_data() -> None:
    # run indicator 0x12, data 01 02 (no 00 or FF after the first byte, where a longer id's run indicator
    # would be: tests/unit/test_server_id_length.py): the number, a warning, the bytes in hex
    status, out, _ = run_cli(["-n", "--hex", "11 11", "--hex", "11 11 04 01 12 01 02", "-V"])
    assert status == 0
    assert "        Run indicator: Unknown (0x12)\n        Additional data: 0102\n" in out
    assert "Warning: run indicator 0x12 is neither 0x00 (OFF) nor 0xFF (ON)" in out
    # byte count 1: the server id alone (data/modbus.toml ?(byte_count-1)), the run indicator missing
    status, out, _ = run_cli(["-n", "--hex", "11 11", "--hex", rtu("11 11 01 B4").hex(" "), "--json"])
    answer = json.loads(out.splitlines()[1])
    assert answer["warnings"] == ["no run indicator status: byte count 1 holds the server id alone"]
    assert answer["fields"] == {"byte_count": 1, "server_id": 180}
