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
