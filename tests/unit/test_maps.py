"""Register maps: the shipped CSVs load, rows parse exactly, bad lines are reported with their number."""
from __future__ import annotations

import pytest

from dissector.devices.maps import (
    COLUMNS,
    ProfileError,
    interpret,
    load_builtin_map,
    load_map_file,
    parse_map,
)

HEADER = ",".join(COLUMNS[:10])  # the 16-bit columns (type and order: test_field_maps.py)


def test_atv71_map_keeps_the_reference_rows_and_sources() -> None:
    rows = load_builtin_map("atv71.csv")
    assert len(rows) == 52
    chcf = rows[8401]
    assert (chcf.code, chcf.name, chcf.access, chcf.source) == ("CHCF", "Profile", "RW", "S")
    assert chcf.enum == {1: "SIM (combined)", 2: "SEP (separate)", 3: "IO (I/O profile)"}
    sfr = rows[3102]
    assert (sfr.code, sfr.unit, sfr.scale, sfr.decimals, sfr.source) == ("SFR", "kHz", 0.1, 1, "A")
    assert rows[3015].source == "F"
    assert rows[9001].scale is None  # ACC: depends on the ramp increment
    assert rows[7121].enum[99] == "CSF"


def test_atv71_status_and_control_words_have_sourced_bits() -> None:
    rows = load_builtin_map("atv71.csv")
    eta = rows[3201]
    assert eta.source == "AC"
    assert eta.bits[0] == "Ready to switch on"
    assert eta.bits[15] == "Direction of rotation"
    assert eta.ambiguous_8000  # bit 15 is a real bit: 16#8000 can be a true status word
    assert rows[8603].bits == eta.bits and rows[8603].source == "FC"
    cmd = rows[8501]
    assert (cmd.bits[0], cmd.bits[7], cmd.bits[8]) == ("Switch on", "Fault reset", "Halt")
    assert not rows[8401].ambiguous_8000


def test_sel_map_is_a_header_only() -> None:
    assert load_builtin_map("sel749m.csv") == {}


def test_interpret_scaled_enum_bits_signed() -> None:
    rows = parse_map(
        HEADER
        + "\n3103,TFR,Maximum output frequency,Hz,0.1,RW,,,,A"
        + "\n8401,CHCF,Profile,,,RW,1=SIM;3=IO (I/O profile),,,S"
        + "\n3201,ETA,Status word,,,R,,0=Ready;2=Running;15=Reverse,,A"
        + "\n5,T,Torque,%,1,R,,,1,X"
        + "\n6,N,Plain,,,R,,,,X",
        "t.csv",
    )
    assert interpret(rows[3103], 600) == (60.0, "60.0 Hz")
    assert interpret(rows[3103], 0) == (0.0, "0.0 Hz")
    assert interpret(rows[8401], 3) == (None, "IO (I/O profile)")
    assert interpret(rows[8401], 9) == (None, "9 (not a listed value)")
    assert interpret(rows[3201], 0x8005) == (None, "Ready, Running, Reverse")
    assert interpret(rows[3201], 0x0002) == (None, "bit 1")
    assert interpret(rows[3201], 0) == (None, "no bit set")
    assert interpret(rows[5], 0xFFFB) == (-5, "-5 %")
    assert interpret(rows[6], 1234) == (None, None)
    assert rows[5].ambiguous_8000 and not rows[6].ambiguous_8000


def test_partial_header_hex_addresses_and_quoted_commas() -> None:
    rows = parse_map('# user map\ncode,address,name\nSPD,0x0010,"Speed, actual"\nX,16#20,\n', "u.csv")
    assert rows[16].code == "SPD" and rows[16].name == "Speed, actual"
    assert rows[32].code == "X" and rows[32].name is None and rows[32].unit is None


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("abc,X,,,,,,,,", "t.csv:3: address 'abc' is not a number"),
        ("70000,X,,,,,,,,", "t.csv:3: address 70000 is outside 0..65535"),
        ("1,,,,,,,,,", "t.csv:3: code is empty"),
        ("1,X,,,ten,,,,,", "t.csv:3: scale 'ten' is not a number"),
        ("1,X,,,,RX,,,,", "t.csv:3: access 'RX' is not R, W or RW"),
        ("1,X,,,,,1=A;B,,,", "t.csv:3: enum entry 'B' is not `number=label`"),
        ("1,X,,,,,,16=Bit,,", "t.csv:3: bits entry '16=Bit': 16 is outside 0..15"),
        ("1,X,,,,,,,yes,", "t.csv:3: signed 'yes' is not 1, 0 or empty"),
        ("1,X,,,,,", "t.csv:3: 7 fields, the header has 10 (quote a field that holds a comma)"),
        ("7,Y,,,,,,,,", "t.csv:3: address 7 already defined on line 2"),
    ],
)
def test_malformed_line_is_reported_with_its_number(line: str, message: str) -> None:
    with pytest.raises(ProfileError) as caught:
        parse_map(f"{HEADER}\n7,X,,,,,,,,\n{line}\n", "t.csv")
    assert str(caught.value) == message


def test_header_errors() -> None:
    with pytest.raises(ProfileError, match=r"^t.csv:2: unknown column 'adress'"):
        parse_map("# c\nadress,code\n", "t.csv")
    with pytest.raises(ProfileError, match=r"^t.csv:1: the header lacks the 'code' column$"):
        parse_map("address,name\n", "t.csv")
    with pytest.raises(ProfileError, match=r"^t.csv: no header line"):
        parse_map("# only a comment\n", "t.csv")


def test_map_file_errors_name_the_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "bad.csv"
    path.write_text("address,code\n1,A\n2\n", encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        load_map_file(path)
    assert str(caught.value) == f"{path}:3: 1 fields, the header has 2 (quote a field that holds a comma)"
    with pytest.raises(ProfileError, match="cannot read the map"):
        load_map_file(tmp_path / "missing.csv")
