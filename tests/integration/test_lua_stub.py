"""The plugin under a plain Lua 5.4 interpreter (the Lua of Wireshark 4.4+) with a stub of the Wireshark API.

tshark 4.0 here runs Lua 5.2 (the parity tests); this runs the same file under 5.4, where there is no `bit`
library and `/` always gives floats, through lua/tests/wireshark_stub.lua: both dissection passes over the
records, then the second pass's tree is printed one `field=value` line per item and checked exactly.
"""
from __future__ import annotations

import random
import subprocess

from lua_harness import PLUGIN, ROOT, ensure_tool
from seed_frames import (
    DEVICE_ID_REQUEST,
    DEVICE_ID_RESPONSE,
    SCENARIO_1,
    SCENARIO_2,
    SCENARIO_3,
    SCENARIO_REQUEST,
)

RUNNER = ROOT / "lua" / "tests" / "run_records.lua"


def run(records: list[tuple[bytes | None, float]], *options: str, fields: tuple[str, ...] = ()) -> list[str]:
    lua = ensure_tool("lua5.4", "lua5.4")
    args = [lua, str(RUNNER), str(PLUGIN)]
    for option in options:
        args += ["-o", option]
    for field in fields:
        args += ["-f", field]
    args += ["!error" if data is None else f"{data.hex()}@{time}" for data, time in records]
    result = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[-1] == "lua version: Lua 5.4"
    return lines[:-1]


def section(lines: list[str], record: int) -> list[str]:
    start = next(index for index, line in enumerate(lines) if line.startswith(f"record {record}:"))
    end = next((index for index in range(start + 1, len(lines)) if lines[index].startswith("record ")), len(lines))
    # (vw3.offset, the stream offset, is checked against vw3-decode by the tshark parity tests)
    return [line.strip() for line in lines[start:end] if not line.strip().startswith("vw3.offset=")]


def test_p38_protection_story_under_lua54() -> None:
    # (forced: under profile auto one answer is no evidence, issue 26, and frame 2 would be generic)
    lines = run([(SCENARIO_REQUEST, 1.0), (SCENARIO_1, 1.012), (SCENARIO_REQUEST, 2.0), (SCENARIO_2, 2.011),
                 (SCENARIO_REQUEST, 3.0), (SCENARIO_3, 3.0095)], "profiles=atv71")
    assert section(lines, 4) == [
        "record 4: 12 Read Holding Registers response 8400..8402 (3)",
        "vw3: VW3 Modbus RTU, 12 Read Holding Registers response 8400..8402 (3)",
        "vw3.item=4", "vw3.kind=2", "vw3.mode=rtu", "vw3.slave=12", "vw3.function=3",
        "vw3.function_name=Read Holding Registers", "vw3.profile=atv71", "vw3.crc=9422", "vw3.crc_expected=9422", "vw3.crc_ok=true", "vw3.start=8400", "vw3.quantity=3",
        "vw3.byte_count=6",  # the PDU's byte count, as vw3-decode -V lists it
        "vw3.reg=Register 8400 = 32768: 16#8000: non-existent (address not in the map) [non-existent]",
        "vw3.reg.address=8400", "vw3.reg.value=32768",
        "vw3.reg.text=16#8000: non-existent (address not in the map)", "vw3.reg.status=non-existent",
        "expert:vw3.expert.protected=Register 8400: 16#8000: non-existent (address not in the map)",
        "vw3.reg=Register 8401 CHCF = 32768: 16#8000: protected [protected]",
        "vw3.reg.address=8401", "vw3.reg.value=32768", "vw3.reg.code=CHCF", "vw3.reg.name=Profile",
        "vw3.reg.text=16#8000: protected", "vw3.reg.source=S", "vw3.reg.status=protected",
        "expert:vw3.expert.protected=Register 8401 CHCF: 16#8000: protected",
        "vw3.reg=Register 8402 COP = 2: Cd (command) [ok]",
        "vw3.reg.address=8402", "vw3.reg.value=2", "vw3.reg.code=COP", "vw3.reg.name=Copy channel 1 <> 2",
        "vw3.atv71.cop=2",  # the per-parameter field (no scale: the value)
        "vw3.reg.text=Cd (command)", "vw3.reg.source=S", "vw3.reg.status=ok",
        "vw3.request_frame=3", "vw3.response_time=0.011000000",
        "vw3.note=CHCF (8401) became protected: read 3 in frame #2, 16#8000 now",
        "expert:vw3.expert.note=CHCF (8401) became protected: read 3 in frame #2, 16#8000 now",
    ]
    exception = section(lines, 6)
    assert "vw3.exception_code=2" in exception
    assert "vw3.request_frame=5" in exception
    assert (
        "vw3.note=exception 02 from the VW3 A3 303: every parameter of this read is non-existent or "
        "protected: 8400 non-existent, "
        "CHCF (8401) protected, COP (8402) protected" in exception
    )
    assert "vw3.note=COP (8402) became protected: read 2 in frame #4, exception 02 now" in exception


def test_device_identification_and_a_record_with_two_frames() -> None:
    lines = run([(DEVICE_ID_REQUEST + DEVICE_ID_RESPONSE, 5.0)])
    record = section(lines, 1)
    # (one record: its second pass keeps the single pass's view, as vw3-decode reading it once: the
    # request, read before the identification that follows it, is provisional)
    # (the Info as vw3-decode's: the objects' values, the revision as the ATV71 profile reads it)
    assert record[0] == ("record 1: 2 Encapsulated Interface Transport request Read Device Identification, basic, "
                         "from object 0 [provisional]; 2 Encapsulated Interface Transport response Read Device "
                         "Identification, basic: VendorName='Telemecanique' ProductCode='ATV71HU15M3' "
                         "MajorMinorRevision=V2.1 UserApplicationName='MACHINE 4'")
    assert "vw3.request_frame=1" in record and "vw3.response_frame=1" in record
    objects = [line for line in record if line.startswith("vw3.object")]
    assert objects[:5] == ["vw3.object=VendorName: 'Telemecanique'", "vw3.object.id=0",
                           "vw3.object.name=VendorName", "vw3.object.value=Telemecanique",
                           "vw3.object.text=manufacturer name"]
    assert "vw3.object.text=V2.1" in objects
    assert "expert:vw3.expert.record.multiple=This record holds 2 frames" in record


def test_ascii_mode_bad_lrc_and_preferences() -> None:
    good = b":02062329000AA2\r\n"
    bad = b":02062329000AA3\r\n"
    lines = run([(good, 1.0), (good, 1.01), (bad, 2.0)], "profiles=2=sel749m", "address_style=3")
    first = section(lines, 1)
    assert "vw3.mode=ascii" in first and "vw3.slave=2" in first and "vw3.function=6" in first
    assert "vw3.reg.label=49002" in first  # 40001 + 9001: the SEL profile's PLC references
    third = section(lines, 3)
    assert "vw3.crc=163" in third and "vw3.crc_expected=162" in third and "vw3.crc_ok=false" in third
    assert "expert:vw3.expert.crc_bad=Bad LRC: 0xA3, expected 0xA2" in third


def test_garbage_never_raises_under_lua54() -> None:
    rng = random.Random(54)
    records = [(rng.randbytes(rng.randint(0, 300)), index * 0.001) for index in range(300)]
    records += [(SCENARIO_1[: rng.randint(0, len(SCENARIO_1))], 1.0) for _ in range(50)]
    lines = run(records)
    assert sum(line.startswith("record ") for line in lines) == len(records)


def test_modbus_tcp_post_dissector_under_lua54() -> None:
    fields = ("mbtcp.unit_id=0", "modbus.func_code=3", "modbus.regnum16=3102,3103",
              "modbus.regval_uint16=40,600", "modbus.request_frame=1")
    # (forced: under profile auto one read is no evidence, issue 26)
    lines = [line.strip() for line in run([(b"\xff", 1.0)], "profiles=atv71", fields=fields)]
    start = next(index for index, line in enumerate(lines) if line.startswith("vw3names:"))
    assert lines[start:] == [
        "vw3names: VW3 register names (Altivar 71 (VW3 A3 303 Modbus card), unit 0)",
        "vw3.reg=Register 3102 SFR = 40: 4.0 kHz [ok]",
        "vw3.reg.address=3102", "vw3.reg.value=40", "vw3.reg.code=SFR", "vw3.reg.name=Switching frequency",
        "vw3.reg.unit=kHz", "vw3.reg.scaled=4.0", "vw3.atv71.sfr=4.0", "vw3.reg.text=4.0 kHz", "vw3.reg.source=A", "vw3.reg.status=ok",
        "vw3.reg=Register 3103 TFR = 600: 60.0 Hz [ok]",
        "vw3.reg.address=3103", "vw3.reg.value=600", "vw3.reg.code=TFR", "vw3.reg.name=Maximum output frequency",
        "vw3.reg.unit=Hz", "vw3.reg.scaled=60.0", "vw3.atv71.tfr=60.0", "vw3.reg.text=60.0 Hz", "vw3.reg.source=A", "vw3.reg.status=ok",
    ]


def test_an_error_inside_the_plugin_is_shown_and_contained() -> None:
    # A record the plugin fails on (here: its bytes cannot be read) says so, and the pairing of the
    # records around it is not disturbed.
    lines = run([(SCENARIO_REQUEST, 1.0), (None, 1.005), (SCENARIO_1, 1.01)])
    broken = section(lines, 2)
    assert broken[1] == "vw3: nil"
    assert broken[2].startswith("expert:vw3.expert.internal=Lua Error in vw3.lua: ")
    assert broken[2].endswith("unreadable bytes")
    assert "vw3.request_frame=1" in section(lines, 3)
