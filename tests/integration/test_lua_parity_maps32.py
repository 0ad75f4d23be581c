"""User register maps with 32-bit rows in the Wireshark plugin, as `vw3-decode --map` reads them.

A map row of type uint32, int32 or float32 spans its register and the next, in ABCD (high word first) or
CDAB order; the value is read on the first register (`words` 2), the second says it continues it
(`words` 0). Maps come as spreadsheets save them: a BOM, `;` separators and decimal commas. Real tshark
4.0.17 with lua/vw3.lua against `vw3-decode --json`: every register's value, scaled value, text, status
and words, exact; map errors with the same `file:line: what` as vw3-decode.
"""
from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

import pytest

from lua_compare import compare
from lua_harness import ROOT, lua_items, python_items, write_pcap
from lua_session import frame

from dissector.model import Kind

# As European Excel saves "CSV UTF-8": BOM, `;`, decimal commas in scale.
WIDE_MAP = "\ufeff" + """# rows of a meter's map (invented for the test)
address;code;name;unit;scale;type;order
100;ENERGY;Energy counter;kWh;0,1;uint32;
102;POWER;Active power;W;;int32;CDAB
104;TEMPF;Temperature;C;;float32;
106;FLOW;Flow;m3/h;0,01;float32;CDAB
108;COUNT;Counter;;;uint16;
109;SPEED;Speed;rpm;;int16;
110;BIG;Signed total;;;int32;ABCD
112;RATIO;Ratio;;;float32;cdab
"""


def _words(value: float | int, kind: str, swapped: bool = False) -> list[int]:
    raw = struct.pack(">f", value) if kind == "float32" else struct.pack(">i" if value < 0 else ">I", value)
    high, low = struct.unpack(">HH", raw)
    return [low, high] if swapped else [high, low]


def _read(slave: int, start: int, values: list[int], function: int = 3) -> list[bytes]:
    request = frame(slave, function, Kind.REQUEST, start=start, quantity=len(values))
    return [request, frame(slave, function, Kind.RESPONSE, byte_count=2 * len(values), values=values)]


def wide_session(slave: int) -> list[tuple[bytes, float]]:
    frames: list[bytes] = []
    # the whole map in one read: every type and order
    values = (_words(100000, "uint32") + _words(-1234, "int32", True) + _words(21.5, "float32")
              + _words(12.34, "float32", True) + [0x8000, 0xFF9C] + _words(-2147483648, "int32")
              + _words(0.1, "float32", True))
    frames += _read(slave, 100, values)
    frames += _read(slave, 100, values[:12], function=4)
    # begins on a second word, ends on a first word: neither is a value
    frames += _read(slave, 101, [0x0001, 0xFB2E, 0xFFFF, 0x8000])
    # float32 that JSON cannot hold, a subnormal, minus zero (its first word is 16#8000), the largest
    for special in (0x7FC00000, 0x7F800000, 0xFF800000, 0x00000001, 0x80000000, 0x7F7FFFFF):
        frames += _read(slave, 104, [special >> 16, special & 0xFFFF])
    frames += _read(slave, 103, [0x8000, 0x8000])  # 103: a second word alone; 104: a first word alone
    # writes: FC16 carries whole values, FC6 one word of one
    words = _words(4000000000, "uint32") + _words(-5, "int32", True)
    frames.append(frame(slave, 16, Kind.REQUEST, start=100, quantity=4, byte_count=8, values=words))
    frames.append(frame(slave, 16, Kind.RESPONSE, start=100, quantity=4))
    single = frame(slave, 6, Kind.REQUEST, address=100, value=7)
    frames += [single, single]
    return [(data, 1767225600.0 + 0.02 * index) for index, data in enumerate(frames)]


def _registers(python: list, address: int) -> list[dict]:
    return [reg for item in python for reg in item.data.get("registers", []) if reg["address"] == address]


def test_wide_rows_for_every_slave(tmp_path: Path) -> None:
    # --map FILE (every slave): slave 20 has no device (generic) and reads the meter's rows.
    wide = tmp_path / "meter.csv"
    wide.write_text(WIDE_MAP, encoding="utf-8")
    pcap = write_pcap(tmp_path / "wide.pcap", wide_session(20))
    python = python_items(pcap, [], "--map", str(wide))
    lua, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:{wide}")
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    assert not any("Preferences" in text for _, text in record_experts)
    first = next(item.data for item in python if item.data["kind"] == "response")
    shown = [(reg["address"], reg.get("scaled"), reg.get("text"), reg.get("words", 1)) for reg in first["registers"]]
    assert shown == [
        (100, 10000.0, "10000.0 kWh", 2), (101, None, "second word of ENERGY", 0),
        (102, -1234, "-1234 W", 2), (103, None, "second word of POWER", 0),
        (104, 21.5, "21.5 C", 2), (105, None, "second word of TEMPF", 0),
        (106, 0.1234, "0.1234 m3/h", 2), (107, None, "second word of FLOW", 0),  # 12.34 * 0.01: no rounding
        (108, None, None, 1), (109, -100, "-100 rpm", 1),  # no scale: shown as is, in its unit
        (110, -2147483648, "-2147483648", 2), (111, None, "second word of BIG", 0),
        (112, pytest.approx(0.1), "0.1", 2), (113, None, "second word of RATIO", 0),
    ]
    texts = [reg.get("text") for reg in _registers(python, 104)]
    # (nan and infinities: no number JSON can hold, so no scaled value and no unit)
    assert {"nan", "inf", "-inf", "1e-45 C", "-0 C", "3.4028235e+38 C",
            "first word of the float32, the second is not in this frame"} <= set(texts)
    assert "first word of the uint32, the second is not in this frame" in [
        reg.get("text") for reg in _registers(python, 100)]
    assert 4000000000 / 10 in [reg.get("scaled") for reg in _registers(python, 100)]


def test_wide_rows_on_a_device_with_16_8000(tmp_path: Path) -> None:
    # atv71=FILE: the rows join the ATV71 map (profile auto chooses it for slave 12 from its first read,
    # answered twice with 16#8000 at 8400: one answer is no evidence, issue 26), where 16#8000 means
    # protected: never for a word of a 32-bit value; ambiguous for a lone first word.
    wide = tmp_path / "meter.csv"
    wide.write_text(WIDE_MAP.replace(";", ",").replace("0,1", "0.1").replace("0,01", "0.01"), encoding="utf-8")
    first = _read(12, 8400, [0x8000, 3, 2]) * 2
    records = [(data, 1767225599.0 + 0.1 * index) for index, data in enumerate(first)]
    records += wide_session(12)
    pcap = write_pcap(tmp_path / "wide-atv71.pcap", records)
    python = python_items(pcap, [], "--map", f"atv71={wide}")
    lua, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:atv71={wide}")
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    statuses = {(reg["address"], reg.get("words", 1), reg.get("status")) for reg in _registers(python, 103)
                + _registers(python, 104) + _registers(python, 108)}
    assert (103, 1, "ambiguous") in statuses  # a second word alone: 16#8000 may be its real low word
    assert (104, 1, "ambiguous") in statuses  # a first word alone: 16#8000 may be its real high word
    assert (104, 2, "ok") in statuses  # -0.0 as float32: 16#8000 0000
    assert (108, 1, "protected") in statuses  # COUNT, a 16-bit row, reads 16#8000


@pytest.mark.parametrize("rows, message", [
    ("1,A,uint32,\n2,B,,\n", "map.csv:3: address 2 is the second register of A (uint32, line 2)"),
    ("1,A,int64,\n", "map.csv:2: type 'int64' is not one of uint16, int16, uint32, int32, float32"),
    ("1,A,uint32,BADC\n", "map.csv:2: order 'BADC' is not ABCD or CDAB"),
    ("65535,A,float32,\n", "map.csv:2: a float32 value needs two registers: 65535 is the last address"),
    # (a cell in Python's repr, quotes as Python picks them; a quote left open: test_map_spreadsheet_saves)
    ("x1,A,,\n", "map.csv:2: address 'x1' is not a number"),
    ('1,"A,uint32,\n', "map.csv:2: a quoted field is not closed on this line (a line break inside a cell? "
                      "write each row on one line)"),
])
def test_wide_row_errors_are_shown_as_vw3_decode_says_them(tmp_path: Path, rows: str, message: str) -> None:
    bad = tmp_path / "map.csv"
    bad.write_text("address,code,type,order\n" + rows)
    pcap = write_pcap(tmp_path / "one.pcap", wide_session(20)[:2])
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", str(bad)], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert cli.returncode != 0 and cli.stderr.strip().endswith(message), cli.stderr
    _, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:{bad}")
    assert any(text.endswith(message) for _, text in record_experts), (message, record_experts)


def test_wide_values_under_lua54(tmp_path: Path) -> None:
    # Wireshark 4.4+ runs Lua 5.4, where 32-bit sums are integers and `/` gives floats: the texts and
    # words and scaled values of every register are those vw3-decode gives (the plugin on the stub of lua/tests).
    import json

    from test_lua_stub import run

    wide = tmp_path / "meter.csv"
    wide.write_text(WIDE_MAP, encoding="utf-8")
    records = wide_session(20)
    pcap = write_pcap(tmp_path / "wide.pcap", records)
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--json", "--map", str(wide)], cwd=ROOT,
                         capture_output=True, text=True, timeout=120, check=True)
    expected = [(reg.get("text"), reg.get("words", 1), reg.get("scaled")) for line in cli.stdout.splitlines()
                for reg in json.loads(line).get("registers", [])]
    got: list[list] = []
    for line in (line.strip() for line in run(records, f"maps={wide}")):
        # a register's line, then its own fields (text, words) before the next register's line
        if line.startswith("vw3.reg="):
            got.append([None, 1, None])
        elif line.startswith("vw3.reg.text="):
            got[-1][0] = line.split("=", 1)[1]
        elif line.startswith("vw3.reg.words="):
            got[-1][1] = int(line.split("=", 1)[1])
        elif line.startswith("vw3.reg.scaled="):
            got[-1][2] = pytest.approx(float(line.split("=", 1)[1]))
    got = [tuple(reg) for reg in got]
    assert got == expected and len(expected) > 40
    assert sum(reg[2] is not None for reg in expected) > 15
