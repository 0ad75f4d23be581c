"""Device profiles and annotation: exact fields for exact bytes (VW3 A3 303 manual, SEL-749M Appendix D)."""
from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from dissector.protocol.crc import with_crc
from dissector.model import Frame, Kind
from dissector.pipeline import dissect_bytes
from dissector.app.profile_options import add_profile_arguments, annotator_from_args
from dissector.devices.build import build_annotator
from dissector.devices.profiles import ProfileError, load_profile

# Seed 000 (card manual p.38): the same read of 8400..8402 from slave 12, three times.
P38_REQUEST = "0C0320D000030EEF"
P38_SCENARIO_1 = "0C030680000003000217E4"
P38_SCENARIO_2 = "0C0306800080000002CE24"
P38_SCENARIO_3 = "0C83025132"
# Worked FC3 example of the card manual.
FC3_REQUEST = "02030C1E0004276C"
FC3_RESPONSE = "0203080028025801F4000052B0"
# Seed 001 (p.32): Read Device Identification of slave 2, 55-byte response.
FC43_REQUEST = "022B0E01003477"
FC43_RESPONSE = (
    "022B0E0102000004"
    + "000D" + b"Telemecanique".hex()
    + "010B" + b"ATV71HU15M3".hex()
    + "0204" + b"0201".hex()
    + "0609" + b"MACHINE 4".hex()
    + "6F50"
)


def frames(hex_text: str, profiles: list[str] | None = None, maps: list[str] | None = None,
           style: str | None = None) -> list[Frame]:
    chosen = list(profiles or [])
    if all("=" in profile for profile in chosen):
        # These tests are about a profile's semantics: the ATV71 as every slave's default, as before
        # profile `auto` (tests/unit/test_auto_profile.py) became the default.
        chosen.append("atv71")
    annotate = build_annotator(chosen, maps or [], style)
    items = dissect_bytes(bytes.fromhex(hex_text), annotate=annotate)
    assert all(isinstance(item, Frame) for item in items), items
    return items  # type: ignore[return-value]


def crc(hex_text: str) -> str:
    return with_crc(bytes.fromhex(hex_text)).hex()


def statuses(frame: Frame) -> list[tuple[int | None, str | None, str | None]]:
    return [(r.address, r.code, r.status) for r in frame.registers or []]


def test_p38_three_scenarios_in_one_capture() -> None:
    capture = (P38_REQUEST + P38_SCENARIO_1 + P38_REQUEST + P38_SCENARIO_2
               + P38_REQUEST + P38_SCENARIO_3)
    items = frames(capture, ["atv71"])
    assert [item.kind for item in items] == [Kind.REQUEST, Kind.RESPONSE] * 2 + [
        Kind.REQUEST, Kind.EXCEPTION]
    one, two, three = items[1], items[3], items[5]
    # Scenario 1: CHCF and COP read, 16#8000 for the non-existent 8400.
    assert statuses(one) == [(8400, None, "non-existent"), (8401, "CHCF", "ok"), (8402, "COP", "ok")]
    assert [r.text for r in one.registers] == [
        "16#8000: non-existent (address not in the map)", "IO (I/O profile)", "Cd (command)"]
    assert one.notes == [] and one.warnings == []
    # Scenario 2: CHCF protected now; the annotator tells it became so.
    assert statuses(two) == [(8400, None, "non-existent"), (8401, "CHCF", "protected"),
                             (8402, "COP", "ok")]
    assert two.registers[1].text == "16#8000: protected" and two.registers[1].scaled is None
    assert two.notes == ["CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"]
    # Scenario 3: everything non-existent or protected -> exception 02, explained.
    assert three.exception_code == 2
    # The device meaning once, with the parameters it is about (the spec name is in the Info column).
    assert three.notes == [
        "exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
        "8400 non-existent, CHCF (8401) protected, COP (8402) protected",
        "COP (8402) became protected: read 2 in frame #4, exception 02 now",
    ]
    assert three.warnings == []


def test_parameter_readable_again_after_protection() -> None:
    items = frames(P38_REQUEST + P38_SCENARIO_2 + P38_REQUEST + P38_SCENARIO_1)
    assert items[3].notes == ["CHCF (8401) readable again: protected in frame #2, 3 now"]


def test_worked_fc3_example_is_named_and_scaled() -> None:
    response = frames(FC3_REQUEST + FC3_RESPONSE)[1]  # atv71 is the default profile
    assert [(r.code, r.scaled, r.text, r.unit, r.status, r.source) for r in response.registers] == [
        ("SFR", 4.0, "4.0 kHz", "kHz", "ok", "A"),
        ("TFR", 60.0, "60.0 Hz", "Hz", "ok", "A"),
        ("HSP", 50.0, "50.0 Hz", "Hz", "ok", "A"),
        ("LSP", 0.0, "0.0 Hz", "Hz", "ok", "A"),
    ]
    assert [r.name for r in response.registers][:2] == ["Switching frequency", "Maximum output frequency"]
    assert [r.label for r in response.registers] == [None] * 4  # protocol addresses by default


def test_generic_profile_names_nothing_and_sets_no_status() -> None:
    response = frames(FC3_REQUEST + FC3_RESPONSE, ["generic"])[1]
    assert [(r.code, r.text, r.status) for r in response.registers] == [(None, None, None)] * 4


def test_single_register_read_of_8000_is_a_value() -> None:
    # One parameter alone: an unreadable one would draw exception 02, so 16#8000 is its value.
    items = frames(crc("0C0320D10001") + crc("0C03028000"))
    assert statuses(items[1]) == [(8401, "CHCF", "ok")]
    assert items[1].registers[0].text == "32768 (not a listed value)"


def test_8000_in_a_status_word_is_ambiguous() -> None:
    items = frames(crc("02030C810002") + crc("0203048000000A"))
    eta, rfr = items[1].registers
    assert (eta.code, eta.status, eta.text) == ("ETA", "ambiguous", "Direction of rotation")
    assert (rfr.code, rfr.status, rfr.text) == ("RFR", "ok", "1.0 Hz")


def test_status_word_bits_by_name() -> None:
    items = frames(crc("02030C810001") + crc("0203020637"))
    assert items[1].registers[0].text == (
        "Ready to switch on, Switched on, Operation enabled, Voltage enabled, Quick stop inactive, "
        "Remote, Target reached")


def test_cmd_bits_not_named_in_io_profile() -> None:
    write_cmd = crc("0206213500 0F".replace(" ", ""))
    chcf_io = crc("020320D10002") + crc("020304 0003 0002".replace(" ", ""))
    chcf_sim = crc("020320D10002") + crc("020304 0001 0002".replace(" ", ""))
    named = frames(chcf_sim + write_cmd)
    assert named[2].registers[0].code == "CMD"
    assert named[2].registers[0].text == "Switch on, Enable voltage, No quick stop, Enable operation"
    plain = frames(chcf_io + write_cmd)
    assert (plain[2].registers[0].code, plain[2].registers[0].text) == ("CMD", None)
    assert plain[2].notes == [
        "the capture ends before any response: not known whether it was answered",
        "CHCF = 3 (I/O profile): CMD bits are assigned by configuration",
    ]


def test_device_identification_objects() -> None:
    response = frames(FC43_REQUEST + FC43_RESPONSE)[1]
    assert [(o.name, o.value, o.text) for o in response.objects] == [
        ("VendorName", "Telemecanique", "manufacturer name"),
        ("ProductCode", "ATV71HU15M3", "device catalog number"),
        ("MajorMinorRevision", "0201", "V2.1"),
        ("UserApplicationName", "MACHINE 4",
         "device name ([DEVICE NAME], 7.1 USER PARAMETERS, up to 16 bytes)"),
    ]


def test_atv71_limits_beyond_the_card_within_the_spec() -> None:
    read64 = frames(crc("02030C1E0040"))[0]
    assert read64.warnings == [
        "quantity 64 is beyond the VW3 A3 303's limit of 63 words for Read Holding Registers"]
    assert frames(crc("02030C1E003F"))[0].warnings == []
    values = "0000" * 62
    write62 = frames(crc("02100C1E003E7C" + values))[0]
    assert write62.warnings == [
        "quantity 62 is beyond the VW3 A3 303's limit of 61 words for Write Multiple Registers"]
    rw = frames(crc("02170C1E00150C1E000102" + "0000"))[0]
    assert rw.warnings == [
        "read quantity 21 is beyond the VW3 A3 303's limit of 20 words for Read/Write Multiple Registers"]


def test_atv71_unsupported_function_and_broadcast() -> None:
    coil = frames(crc("020500010000") + crc("028501"))
    assert coil[0].warnings == ["Write Single Coil (5) is not supported by the VW3 A3 303"]
    assert coil[1].notes == ["exception 01 from the VW3 A3 303: function not recognized"]
    broadcast = frames(crc("00170C1E00010C1E000102" + "0000"))[0]
    assert broadcast.broadcast
    # (the spec's rule since FC23 reads: a broadcast only writes; the profile's rule then says nothing more)
    assert broadcast.warnings == ["Read/Write Multiple Registers cannot be broadcast (slave 0)"]
    assert frames(crc("000623290005"))[0].warnings == []


def test_atv71_exceptions_6_7_and_undocumented() -> None:
    six = frames(crc("020620D10001") + crc("028606"))[1]
    assert six.notes == ["exception 06 from the VW3 A3 303: write refused: the drive is in Forced local mode"]
    seven = frames(crc("020620D10001") + crc("028607"))[1]
    assert seven.notes == [
        "exception 07 from the VW3 A3 303: write refused: the motor is running (configuration parameter)"]
    zero = frames(crc("020620D10001") + crc("028600"))[1]
    assert zero.notes == ["exception 00 is not one the VW3 A3 303 documents (01, 02, 03, 04, 06, 07)"]
    assert zero.warnings == ["exception code 0 is not defined by the spec"]


def test_atv71_diagnostics_0f_is_broadcast_count() -> None:
    items = frames(crc("0208000F0000") + crc("0208000F0005"))
    meaning = ("sub-function 0F on the VW3 A3 303: broadcast messages received "
               "(the spec's 0F counts requests not answered)")
    assert items[0].notes == [meaning]
    assert items[1].notes == [meaning + "; value 5"]


def test_write_then_protected_story() -> None:
    write = crc("020620D20002") + crc("020620D20002")
    # 8401..8413, FR1 (8413) read as 1: an answer whose every value is 16#8000 is ambiguous (p.38)
    read = crc("020320D1000D") + crc("02031A" + "8000" * 12 + "0001")
    items = frames(write + read)
    assert statuses(items[3])[:2] == [(8401, "CHCF", "protected"), (8402, "COP", "protected")]
    assert items[3].notes == ["COP (8402) became protected: written 2 in frame #2, 16#8000 now"]


# -- SEL-749M --------------------------------------------------------------------------------------------
def test_sel_exception_meanings_with_counters() -> None:
    over = frames(crc("030300000082") + crc("038303"), ["3=sel749m"])
    assert over[0].warnings == [
        "quantity 130 outside the spec's 1..125",
        "quantity 130 is beyond the SEL-749M's limit of 125 words for Read Holding Registers",
    ]
    assert over[1].notes == [
        "exception 03 from the SEL-749M to Read Holding Registers: illegal number of registers to read "
        "(increments the Illegal Register counter)"]
    format_error = frames(crc("030300000002") + crc("038303"), ["3=sel749m"])[1]
    assert format_error.notes == [
        "exception 03 from the SEL-749M to Read Holding Registers: format error "
        "(increments the Bad Packet Format counter)"]
    address = frames(crc("0306FFFF0001") + crc("038602"), ["3=sel749m"])[1]
    assert address.notes == [
        "exception 02 from the SEL-749M to Write Single Register: illegal register address "
        "(increments the Invalid Address and Illegal Write counters)"]
    values = "0000" * 101
    write = frames(crc("031000000065CA" + values) + crc("039003"), ["3=sel749m"])
    assert write[0].warnings == [
        "quantity 101 is beyond the SEL-749M's limit of 100 words for Write Multiple Registers"]
    assert write[1].notes == [
        "exception 03 from the SEL-749M to Write Multiple Registers: illegal number of registers "
        "(increments the Illegal Register and Illegal Write counters)"]


def test_sel_4x_display_and_protocol_override() -> None:
    capture = crc("030300640002") + crc("0303040001FFFF")
    response = frames(capture, ["sel749m"])[1]
    assert [(r.address, r.label, r.status, r.code) for r in response.registers] == [
        (100, "40101", None, None), (101, "40102", None, None)]
    plain = frames(capture, ["sel749m"], style="protocol")[1]
    assert [r.label for r in plain.registers] == [None, None]
    wide = frames(crc("03032710 0001".replace(" ", "")) + crc("0303020001"), ["sel749m"])[1]
    assert wide.registers[0].label == "410001"  # 6-digit reference past 49999


def test_sel_unsupported_function_and_nop_alone() -> None:
    diag = frames(crc("030800000000"), ["sel749m"])[0]
    assert diag.warnings == ["Diagnostics (8) is not supported by the SEL-749M"]
    nop = frames(crc("037E") + crc("037E"), ["sel749m"])[0]
    assert nop.warnings == ["NOP (126) is only valid inside an encapsulated packet on the SEL-749M"]


def test_fc23_exception_02_is_not_explained_register_by_register() -> None:
    # The write half may be the cause: only the card's meaning is given.
    items = frames(crc("020320D10002") + crc("0203040003 0002".replace(" ", ""))
                   + crc("021720D1000221350001020006") + crc("029702"))
    assert items[3].notes == [
        "exception 02 from the VW3 A3 303: address does not exist "
        "(also: every parameter read is non-existent or protected)"]


def test_json_carries_the_annotation() -> None:
    from dissector.render.jsonout import item_to_dict

    response = frames(P38_REQUEST + P38_SCENARIO_1)[1]
    assert item_to_dict(response)["registers"] == [
        {"address": 8400, "value": 32768, "text": "16#8000: non-existent (address not in the map)",
         "status": "non-existent"},
        {"address": 8401, "value": 3, "code": "CHCF", "name": "Profile", "text": "IO (I/O profile)",
         "status": "ok", "source": "S"},
        {"address": 8402, "value": 2, "code": "COP", "name": "Copy channel 1 <> 2",
         "text": "Cd (command)", "status": "ok", "source": "S"},
    ]


def test_generic_plc_style_uses_3x_for_input_registers() -> None:
    response = frames(crc("010400000001") + crc("0104020007"), ["generic"], style="plc")[1]
    assert response.registers[0].label == "30001"


# -- per-slave profiles and maps --------------------------------------------------------------------------
def test_per_slave_profiles_and_map_targets(tmp_path: Path) -> None:
    sel_map = tmp_path / "sel.csv"
    sel_map.write_text("address,code,name,unit,scale,source\n100,IA,Phase A current,A,0.1,user\n",
                       encoding="utf-8")
    capture = (crc("030300640001") + crc("0303020123")
               + FC3_REQUEST + FC3_RESPONSE)
    items = frames(capture, ["3=sel749m", "atv71"], [f"sel749m={sel_map}"])
    ia = items[1].registers[0]
    assert (ia.code, ia.name, ia.text, ia.source, ia.label) == (
        "IA", "Phase A current", "29.1 A", "user", "40101")
    assert items[3].registers[0].code == "SFR"  # slave 2 keeps the ATV71 map
    only_slave_2 = frames(capture, ["3=sel749m"], [f"2={sel_map}"])
    assert only_slave_2[1].registers[0].code is None


def test_map_overrides_a_builtin_row(tmp_path: Path) -> None:
    override = tmp_path / "mine.csv"
    override.write_text("# my drive\naddress,code,name,unit,scale\n3102,SFR,Carrier,kHz,0.01\n",
                        encoding="utf-8")
    response = frames(FC3_REQUEST + FC3_RESPONSE, maps=[str(override)])[1]
    first, second = response.registers[:2]
    assert (first.name, first.text, first.source) == ("Carrier", "0.40 kHz", None)
    assert (second.code, second.text) == ("TFR", "60.0 Hz")


def test_bad_map_line_is_reported_through_build_annotator(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("address,code,scale\n1,A,1\n2,B,x\n", encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        build_annotator([], [str(bad)], None)
    assert str(caught.value) == f"{bad}:3: scale 'x' is not a number"


@pytest.mark.parametrize(
    ("profiles", "maps", "message"),
    [
        (["atv7"], [], "unknown profile 'atv7' (built-in: atv71, sel749m, generic; or a .toml file)"),
        (["atv71", "auto"], [], "--profile 'auto': a default profile (atv71) is already set"),
        (["3=auto"], [], "--profile '3=auto': auto is for every slave (--profile auto)"),
        (["300=atv71"], [], "--profile '300=atv71': slave 300 is outside 0..247"),
        (["x=atv71"], [], "--profile 'x=atv71': 'x' is not a slave address"),
        (["atv71", "generic"], [], "--profile 'generic': a default profile (atv71) is already set"),
        (["3=atv71", "3=generic"], [], "--profile '3=generic': slave 3 already has a profile"),
        ([], ["foo=x.csv"],
         "--map 'foo=x.csv': 'foo' is neither a slave address nor a profile in use (atv71, generic, sel749m)"),
        (["atv71"], ["foo=x.csv"],
         "--map 'foo=x.csv': 'foo' is neither a slave address nor a profile in use (atv71)"),
    ],
)
def test_profile_errors(profiles: list[str], maps: list[str], message: str, tmp_path: Path,
                        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.csv").write_text("address,code\n", encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        build_annotator(profiles, maps, None)
    assert str(caught.value) == message


def test_profile_file_errors_name_the_file(tmp_path: Path) -> None:
    broken = tmp_path / "dev.toml"
    broken.write_text('name = "dev"\nfunctions = [3, "x"]\n', encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        load_profile(str(broken))
    assert str(caught.value) == f"{broken}: functions: 'x' is not a number"
    broken.write_text('name = "dev"\nlimits = 3 3\ntitle = "x"\n', encoding="utf-8")
    with pytest.raises(ProfileError, match=rf"^{broken}: .*line 2"):
        load_profile(str(broken))


def test_user_profile_file_with_its_own_map(tmp_path: Path) -> None:
    (tmp_path / "dev.csv").write_text("address,code,unit,scale\n0,V,V,0.5\n", encoding="utf-8")
    (tmp_path / "dev.toml").write_text(
        'name = "dev"\ndevice = "DEV-1"\nmap = "dev.csv"\nfunctions = [3]\n[limits]\n3 = 2\n',
        encoding="utf-8")
    items = frames(crc("070300000001") + crc("0703020014"), [f"7={tmp_path / 'dev.toml'}"])
    assert (items[1].registers[0].code, items[1].registers[0].text) == ("V", "10.0 V")
    assert frames(crc("070300000003"), [f"7={tmp_path / 'dev.toml'}"])[0].warnings == [
        "quantity 3 is beyond the DEV-1's limit of 2 words for Read Holding Registers"]


def test_command_line_arguments() -> None:
    parser = argparse.ArgumentParser()
    add_profile_arguments(parser)
    args = parser.parse_args(["--profile", "12=atv71", "--profile", "sel749m", "--address-style", "plc"])
    assert (args.profile, args.map, args.address_style) == (["12=atv71", "sel749m"], [], "plc")
    annotate = annotator_from_args(args)
    items = dissect_bytes(bytes.fromhex(P38_REQUEST + P38_SCENARIO_1), annotate=annotate)
    assert [(r.code, r.label) for r in items[1].registers] == [
        (None, "48401"), ("CHCF", "48402"), ("COP", "48403")]
    with pytest.raises(SystemExit):
        parser.parse_args(["--address-style", "modicon"])


def test_names_for_renderers() -> None:
    annotate = build_annotator(["1=sel749m", "atv71"], [], None)
    assert annotate.exception_name(2, 6) == "write refused: the drive is in Forced local mode"
    assert annotate.exception_name(2, 8) == "Memory Parity Error"  # not documented by the card: spec name
    assert annotate.function_name(1, 0x60) == "Read Parameter Information"
    assert annotate.function_name(2, 0x60) == "Function 96"
    assert annotate.subfunction_name(2, 15) == (
        "broadcast messages received (the spec's 0F counts requests not answered)")
    assert annotate.subfunction_name(1, 15) == "Return Server No Response Count"
    assert annotate.label(1, 3, 500) == "40501"
    assert annotate.label(2, 3, 8401) is None


def test_a_revision_with_non_ascii_digits_is_not_read_as_a_version() -> None:
    # Regression (found by the Lua parity fuzz): '0\xb201' is 4 "digits" to str.isdigit().
    from dissector.pipeline import dissect_bytes
    from dissector.devices.build import build_annotator
    from helpers import rtu

    response = rtu("02 2B 0E 01 02 00 00 01 02 04 30 B2 30 31")
    items = dissect_bytes(rtu("02 2B 0E 01 00") + response, annotate=build_annotator(["atv71"], []))
    (obj,) = items[1].objects
    assert (obj.name, obj.value) == ("MajorMinorRevision", r"0\xb201")  # (the byte B2 as \xNN: not ASCII)
    assert obj.text != "V0.1" and not (obj.text or "").startswith("V")
    assert any("MMmm" in note for note in items[1].notes)
