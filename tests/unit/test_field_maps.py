"""Maps as spreadsheets save them: UTF-8 with a BOM, `;` separators and decimal commas (European
Excel's "CSV UTF-8"), told from the header line."""
from __future__ import annotations

from pathlib import Path

import pytest
from helpers import rtu, run_cli

from dissector.devices.maps import load_map_file
from dissector.errors import ProfileError

EXCEL = (
    "\ufeffaddress;code;name;unit;scale;enum\r\n"
    "3102;SFR;Fréquence de découpage;kHz;0,1;\r\n"
    '8401;CHCF;Profil;;;"1=SIM;2=SEP;3=IO"\r\n'
)


def test_a_european_excel_map_is_read(tmp_path: Path) -> None:
    path = tmp_path / "drive.csv"
    path.write_bytes(EXCEL.encode("utf-8"))
    rows = load_map_file(path)
    assert (rows[3102].code, rows[3102].name, rows[3102].scale, rows[3102].decimals) == (
        "SFR", "Fréquence de découpage", 0.1, 1)
    assert rows[8401].enum == {1: "SIM", 2: "SEP", 3: "IO"}
    data = rtu("0C 03 0C1E 0001") + rtu("0C 03 02 0028") + rtu("0C 03 20D1 0001") + rtu("0C 03 02 0003")
    out = run_cli(["-", "--profile", "generic", "--map", str(path)], stdin=data)[1].splitlines()
    assert out[1].endswith("Read Holding Registers 3102: SFR=4.0 kHz [#1]  CRC ok")
    assert out[3].endswith("Read Holding Registers 8401: CHCF=IO [#3]  CRC ok")


def test_tab_separated_and_plain_maps(tmp_path: Path) -> None:
    tabbed = tmp_path / "tabbed.csv"
    tabbed.write_text("address\tcode\tscale\n5\tPV\t0.5\n", encoding="utf-8")
    assert load_map_file(tabbed)[5].scale == 0.5
    plain = tmp_path / "plain.csv"
    plain.write_text("address,code,enum\n7,MODE,1=A;2=B\n", encoding="utf-8")
    assert load_map_file(plain)[7].enum == {1: "A", 2: "B"}


def test_a_semicolon_map_with_a_wrong_field_count_names_the_separator(tmp_path: Path) -> None:
    path = tmp_path / "bad.csv"
    path.write_text("address;code;name\n5;PV;a;b\n", encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        load_map_file(path)
    assert str(caught.value) == f"{path}:2: 4 fields, the header has 3 (quote a field that holds a ';')"


WIDE = """address,code,name,unit,scale,type,order
100,PWR,Active power,kW,0.1,int32,
102,FREQ,Frequency,Hz,,float32,CDAB
104,ENERGY,Energy,kWh,,uint32,
106,TEMP,Temperature,°C,,float32,ABCD
"""


def _wide_capture() -> bytes:
    import struct

    frequency = struct.pack(">f", 50.0)
    body = ((-1234).to_bytes(4, "big", signed=True) + frequency[2:] + frequency[:2]
            + (123456789).to_bytes(4, "big") + struct.pack(">f", -12.5))
    return (rtu("05 03 0064 0008") + rtu("05 03 10" + body.hex())
            + rtu("05 03 0065 0002") + rtu("05 03 04 0001 0002"))


def test_32_bit_values_are_one_value_over_two_registers(tmp_path: Path) -> None:
    import json

    path = tmp_path / "meter.csv"
    path.write_text(WIDE, encoding="utf-8")
    data = _wide_capture()
    out = run_cli(["-", "--map", str(path)], stdin=data)[1].splitlines()
    assert out[1] == (
        "     2            -   5 response  Read Holding Registers 100..107 (8): PWR=-123.4 kW FREQ=50 Hz "
        "ENERGY=123456789 kWh TEMP=-12.5 °C [#1] [provisional]  CRC ok"  # read once under profile auto
    )
    # A read that holds one word of a value says so, the second word as the first.
    assert out[3].endswith("(2): PWR=second word of the int32, the first is not in this frame "
                           "FREQ=first word of the float32, the second is not in this frame [#3] [provisional]  CRC ok")
    registers = json.loads(run_cli(["-", "--map", str(path), "--json"], stdin=data)[1].splitlines()[1])["registers"]
    assert registers[2] == {"address": 102, "value": 0, "code": "FREQ", "name": "Frequency", "unit": "Hz",
                            "scaled": 50.0, "text": "50 Hz", "words": 2}
    assert registers[3]["words"] == 0 and registers[3]["text"] == "second word of FREQ"
    assert [register["scaled"] for register in registers[::2]] == [-123.4, 50.0, 123456789, -12.5]
    detail = run_cli(["-", "--map", str(path), "-V"], stdin=data)[1]
    assert "Register 100: 65535 (0xFFFF)  PWR [Active power]\n" in detail
    assert "Value: -123.4 kW" in detail and "32-bit value: this register and the next" in detail
    # The compiled path leaves a slave with 32-bit rows to the Python stages: the same lines.
    # (profile generic forced: nothing is provisional)
    assert [line.replace(" [provisional]", "") for line in out] == run_cli(
        ["-", "--map", str(path), "--profile", "generic"], stdin=data)[1].splitlines()


@pytest.mark.parametrize(
    ("rows", "message"),
    [
        ("5,X,float32,\n6,Y,,\n", "3: address 6 is the second register of X (float32, line 2)"),
        ("5,X,int64,\n", "2: type 'int64' is not one of uint16, int16, uint32, int32, float32"),
        ("5,X,uint32,BADC\n", "2: order 'BADC' is not ABCD or CDAB"),
        ("65535,X,uint32,\n", "2: a uint32 value needs two registers: 65535 is the last address"),
    ],
)
def test_32_bit_map_errors(rows: str, message: str, tmp_path: Path) -> None:
    path = tmp_path / "bad.csv"
    path.write_text("address,code,type,order\n" + rows, encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        load_map_file(path)
    assert str(caught.value) == f"{path}:{message}"
