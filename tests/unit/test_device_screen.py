"""What the screen shows of device knowledge: PLC-style references by function (0X coils, 1X inputs,
3X input registers, 4X holding registers) and register statuses an exception tells (p.38)."""
from __future__ import annotations

import json
from pathlib import Path

from helpers import rtu, run_cli

from dissector.devices.naming import plc_label

ROOT = Path(__file__).resolve().parents[2]
P38 = ROOT / "captures" / "p38_protection.bin"

COILS_AND_INPUTS = b"".join(
    rtu(text)
    for text in [
        "11 01 00 13 00 25", "11 01 05 CD 6B B2 0E 1B",  # coils 20..56
        "11 02 00 C4 00 16", "11 02 03 AC DB 35",  # discrete inputs 197..218
        "11 05 00 AC FF 00", "11 05 00 AC FF 00",
        "11 04 00 08 00 01", "11 04 02 00 0A",  # input register 9
    ]
)


def test_plc_references_follow_the_modbus_convention_per_function() -> None:
    # --profile generic: read once under auto, these lines would also be [provisional] (issue 27)
    out = run_cli(["-", "--address-style", "plc", "--profile", "generic"], stdin=COILS_AND_INPUTS)[1].splitlines()
    assert [line[34:].split("  CRC")[0] for line in out] == [
        "Read Coils 00020..00056 (37)",
        "Read Coils 00020..00056 (37): 10110011110101100100110101110000… (+5) [#1]",
        "Read Discrete Inputs 10197..10218 (22)",
        "Read Discrete Inputs 10197..10218 (22): 0011010111011011101011 [#3]",
        "Write Single Coil 00173 = ON",
        "Write Single Coil 00173 = ON [#5]",
        "Read Input Registers 30009",
        "Read Input Registers 30009: 30009=10 [#7]",
    ]
    assert json.loads(run_cli(["-", "--address-style", "plc", "--json"], stdin=COILS_AND_INPUTS)[1]
                      .splitlines()[0])["span_label"] == "00020..00056"


def test_plc_labels_past_the_five_digit_range() -> None:
    assert [plc_label(1, 0), plc_label(1, 9998), plc_label(1, 9999)] == ["00001", "09999", "010000"]
    assert [plc_label(40001, 9998), plc_label(40001, 9999), plc_label(10001, 65535)] == [
        "49999", "410000", "165536"]


def test_exception_02_gives_the_registers_their_status_in_json() -> None:
    lines = run_cli([str(P38), "--json"])[1].splitlines()
    registers = json.loads(lines[9])["registers"]
    assert registers == [
        {"address": 8400, "value": None, "text": "no value: exception 02", "status": "non-existent"},
        {"address": 8401, "value": None, "code": "CHCF", "name": "Profile", "text": "no value: exception 02",
         "status": "protected", "source": "S"},
        {"address": 8402, "value": None, "code": "COP", "name": "Copy channel 1 <> 2",
         "text": "no value: exception 02", "status": "protected", "source": "S"},
    ]
    shown = run_cli([str(P38), "-Y", 'status == "protected"'])[1].splitlines()
    assert [int(line.split()[0]) for line in shown] == [6, 8, 10, 12]
    only_cop = run_cli([str(P38), "-Y", 'code == "COP" and status == "protected"'])[1].splitlines()
    assert [int(line.split()[0]) for line in only_cop] == [10, 12]
    detail = run_cli([str(P38), "-V", "-Y", "frame == 10"])[1]
    assert "Register 8401: no value  CHCF [Profile]" in detail and "Status: protected" in detail
