"""A map's columns say one thing (hunt 55, items 1, 7, 8, 9).

A float32 row with a scale: the scale multiplies and the product is written as the float is (fewest
digits), where it was rounded to the scale's decimals and cut to an integer for a scale of 1 or more
(59.95 at scale 1 read `60 kW`, 1.5 at 1000 `1500 W`, 1.25 at 0.1 `0.1 A`). Columns that contradict each
other (a type and a signed cell, CDAB on one register, enum with bits, labels with a scale or a unit), a
scale of 0 (told with a message that contradicted itself) and a code named twice (--watch X followed two
registers) are refused with `file:line: what`. vw3-decode (engine and VW3_PURE_PYTHON=1) and the plugin
(tshark 4.0.17, -2) give the same lines, values and messages."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# Read of 6 registers at 0: 59.95, 1.5, 1.25 as float32 (42 6F CC CD, 3F C0 00 00, 3F A0 00 00).
REQUEST, RESPONSE = rtu("01 03 0000 0006"), rtu("01 03 0C 426F CCCD 3FC0 0000 3FA0 0000")
SCALED = {
    "address,code,unit,scale,type\n0,P,kW,1,float32\n2,Q,W,1000,float32\n4,R,A,0.1,float32\n":
        ("P=59.95 kW Q=1500 W R=0.125 A", [59.95, 1500.0, 0.125]),
    "address,code,unit,scale,type\n0,P,kW,0.001,float32\n2,Q,Hz,0.1,float32\n4,R,A,,float32\n":
        ("P=0.05995 kW Q=0.15 Hz R=1.25 A", [0.05995, 0.15, 1.25]),
    # (a scale that is not a power of ten: 1.5 * 2.5 and 1.25 * 0.3 exactly; negative: the sign follows)
    "address,code,scale,type\n0,P,-1,float32\n2,Q,2.5,float32\n4,R,0.3,float32\n":
        ("P=-59.95 Q=3.75 R=0.375", [-59.95, 3.75, 0.375]),
}

TWO = "swaps the words of a 32-bit value: type"
LABEL = "(its value is a label)"
REFUSED = {
    "address,code,type,signed\n1,X,uint32,1\n": "signed '1' contradicts type uint32",
    "address,code,type,signed\n1,X,int16,0\n": "signed '0' contradicts type int16",
    "address,code,type,signed\n1,X,float32,1\n": "signed '1' contradicts type float32",
    "address,code,type,signed\n1,X,float32,0\n": "signed '0' contradicts type float32",
    "address,code,order\n1,X,CDAB\n": f"order 'CDAB' {TWO} uint16 is one register",
    "address,code,signed,order\n1,X,1,cdab\n": f"order 'CDAB' {TWO} int16 is one register",
    "address,code,enum,bits\n5,EB,1=One,0=Bit0\n": "a register cannot carry both enum and bit labels",
    "address,code,enum,scale\n6,EU,1=One,0.1\n": f"a register with enum labels cannot carry a scale {LABEL}",
    "address,code,enum,unit\n6,EU,1=One,Hz\n": f"a register with enum labels cannot carry a unit {LABEL}",
    "address,code,bits,unit\n6,B,0=On,V\n": f"a register with bit labels cannot carry a unit {LABEL}",
    "address,code,scale\n1,X,0\n": "scale '0' would make every value 0",
    "address,code,scale\n1,X,-0.0\n": "scale '-0.0' would make every value 0",
    "address,code,scale\n1,X,1e13\n": "scale '1e13' is outside ±1e-12..1e+12",
}
# (the line of the second row, its message: a code names one register, as --watch matches it, any case)
CODE_TWICE = "address,code\n1,X\n# a comment\n2,x\n"
CODE_TWICE_MESSAGE = "map.csv:4: code x already names address 1 (line 2)"


def _pcap(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "f.pcap", [(REQUEST, 1767225600.0), (RESPONSE, 1767225600.01)])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
@pytest.mark.parametrize("text", list(SCALED), ids=["scale 1", "scale 0.001", "scale 2.5"])
def test_a_scaled_float32_is_the_product(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                         text: str) -> None:
    use_engine(monkeypatch, pure)
    (tmp_path / "f.csv").write_text(text)
    line, scaled = SCALED[text]
    status, out, err = run_cli(["--map", str(tmp_path / "f.csv"), str(_pcap(tmp_path))])
    assert status == 0, err
    assert out.splitlines()[1] == (
        f"     2     0.010000   1 response  Read Holding Registers 0..5 (6): {line} [#1, 10.0 ms]  CRC ok")
    status, out, err = run_cli(["--map", str(tmp_path / "f.csv"), str(_pcap(tmp_path)), "--json"])
    registers = json.loads(out.splitlines()[1])["registers"]
    assert [reg["scaled"] for reg in registers if reg.get("words") == 2] == scaled


def test_a_scaled_float32_in_the_plugin(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path)
    for number, text in enumerate(SCALED):
        (tmp_path / f"m{number}.csv").write_text(text)
        items, _, _ = lua_items(pcap, "-o", f"vw3.maps:{tmp_path / f'm{number}.csv'}")
        registers = [reg for reg in items[1].registers if reg.get("words") == "2"]
        line, scaled = SCALED[text]
        assert " ".join(f"{reg['code']}={reg['text']}" for reg in registers) == line
        assert [float(reg["scaled"]) for reg in registers] == scaled


@pytest.mark.parametrize("text", [*REFUSED, CODE_TWICE], ids=[*REFUSED.values(), "code twice"])
def test_contradicting_columns_are_refused(tmp_path: Path, text: str) -> None:
    (tmp_path / "map.csv").write_text(text)
    status, out, err = run_cli(["--map", str(tmp_path / "map.csv"), str(_pcap(tmp_path))])
    where = CODE_TWICE_MESSAGE if text == CODE_TWICE else f"map.csv:2: {REFUSED[text]}"
    assert (status, out, err) == (2, "", f"vw3-decode: {tmp_path / where}\n")


def test_contradicting_columns_in_the_plugin(tmp_path: Path) -> None:
    # every map in one preference: each refused with vw3-decode's message, one expert each
    paths = []
    for number, text in enumerate([*REFUSED, CODE_TWICE]):
        folder = tmp_path / str(number)
        folder.mkdir()
        (folder / "map.csv").write_text(text)
        paths.append(str(folder / "map.csv"))
    _, record_experts, _ = lua_items(_pcap(tmp_path), "-o", "vw3.maps:" + ";".join(paths))
    experts = {text for _, text in record_experts}
    for number, text in enumerate(REFUSED):
        message = f"{paths[number]}:2: {REFUSED[text]}"
        assert any(expert.endswith(message) for expert in experts), (message, experts)
    assert any(expert.endswith(str(tmp_path / str(len(REFUSED)) / CODE_TWICE_MESSAGE)) for expert in experts)


# Item 2: a row with a unit and no scale is a number in its unit, `scaled` filled, whatever its type (a
# uint16 said `50 (unscaled, in Hz)` with no scaled value, an int16 `-50 (unscaled, in Hz)` with one, a
# uint32 and a float32 `65538 V`, `1.25 A`). `(unscaled, in s)` is for a scale the device's settings choose,
# which the map says with scale `?` (the ATV71's ACC and DEC: data/maps/atv71.csv).
UNITS = ("address,code,unit,scale,type,signed\n0,U16,Hz,,,\n1,S16,Hz,,,1\n2,U32,V,,uint32,\n"
         "4,F32,A,,float32,\n6,N16,,,,\n7,R,s,?,,\n8,RS,s,?,int16,\n")
UNITS_READ = (rtu("01 03 0000 0009"), rtu("01 03 12 0032 FFCE 0001 0002 3FA0 0000 0007 000A FFF6"))
UNITS_LINE = "U16=50 Hz S16=-50 Hz U32=65538 V F32=1.25 A N16=7 R=10 (unscaled, in s)"  # (RS: `… (+1)`)
UNITS_SCALED = [50, -50, 65538, None, 1.25, None, None, None, -10]


def _units_pcap(tmp_path: Path) -> Path:
    (tmp_path / "u.csv").write_text(UNITS)
    return write_pcap(tmp_path / "u.pcap", [(UNITS_READ[0], 1767225600.0), (UNITS_READ[1], 1767225600.01)])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_unit_without_a_scale_is_a_number_in_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _units_pcap(tmp_path)
    status, out, err = run_cli(["--map", str(tmp_path / "u.csv"), str(pcap)])
    assert status == 0, err
    assert out.splitlines()[1] == ("     2     0.010000   1 response  Read Holding Registers 0..8 (9): "
                                   f"{UNITS_LINE} … (+1) [#1, 10.0 ms]  CRC ok")
    status, out, err = run_cli(["--map", str(tmp_path / "u.csv"), str(pcap), "-T", "registers"])
    assert [line.split("\t")[10:14] for line in out.splitlines()] == [  # scaled, unit, status, text
        ["50", "Hz", "", "50 Hz"], ["-50", "Hz", "", "-50 Hz"], ["65538", "V", "", "65538 V"],
        ["", "V", "", "second word of U32"], ["1.25", "A", "", "1.25 A"], ["", "A", "", "second word of F32"],
        ["", "", "", ""], ["", "s", "", "10 (unscaled, in s)"], ["-10", "s", "", "-10 (unscaled, in s)"]]
    status, out, err = run_cli(["--map", str(tmp_path / "u.csv"), str(pcap), "--json"])
    assert [reg.get("scaled") for reg in json.loads(out.splitlines()[1])["registers"]] == UNITS_SCALED


def test_a_unit_without_a_scale_in_the_plugin(tmp_path: Path) -> None:
    items, _, _ = lua_items(_units_pcap(tmp_path), "-o", f"vw3.maps:{tmp_path / 'u.csv'}")
    registers = items[1].registers
    assert " ".join(f"{reg['code']}={reg['text']}" for reg in registers if "text" in reg
                    and not reg["text"].startswith("second")) == UNITS_LINE.replace(" N16=7", "") + (
                        " RS=-10 (unscaled, in s)")
    assert [reg.get("scaled") and float(reg["scaled"]) for reg in registers] == UNITS_SCALED


UNKNOWN_REFUSED = {
    "address,code,scale\n1,X,?\n": "scale '?' (the device sets it) needs the unit the value counts in",
    "address,code,unit,scale,type\n1,X,s,?,uint32\n":
        "scale '?' (the device sets it) is for a 16-bit register: type uint32 is two",
    "address,code,unit,scale,enum\n1,X,,?,1=a\n": f"a register with enum labels cannot carry a scale {LABEL}",
}


@pytest.mark.parametrize("text", list(UNKNOWN_REFUSED), ids=["no unit", "uint32", "enum"])
def test_a_scale_the_device_sets_is_for_a_16_bit_number(tmp_path: Path, text: str) -> None:
    (tmp_path / "map.csv").write_text(text)
    status, out, err = run_cli(["--map", str(tmp_path / "map.csv"), str(_pcap(tmp_path))])
    assert (status, out, err) == (2, "", f"vw3-decode: {tmp_path / 'map.csv'}:2: {UNKNOWN_REFUSED[text]}\n")
    _, record_experts, _ = lua_items(_pcap(tmp_path), "-o", f"vw3.maps:{tmp_path / 'map.csv'}")
    message = f"{tmp_path / 'map.csv'}:2: {UNKNOWN_REFUSED[text]}"
    assert any(expert.endswith(message) for _, expert in record_experts), (message, record_experts)
