"""-Y and -T fields as Wireshark 4.0 has them (session 54's hunt, defects 5, 6a, 9, 10): the frames each
filter selects on the shipped captures, checked with tshark 4.0.17 running the plugin (`vw3.*`) or on
tshark's own `frame` fields, and the exact text -T fields writes."""
from __future__ import annotations

import pytest

from helpers import run_cli

from conftest import ROOT

NOISY = str(ROOT / "captures" / "noisy_bus.pcap")
ATV71 = str(ROOT / "captures" / "atv71_commissioning.pcap")
SEL = str(ROOT / "captures" / "sel749m_polling.pcap")


def frames(expression: str, *inputs: str) -> list[int]:
    status, out, err = run_cli(["-Y", expression, "-T", "fields", "-e", "frame", *inputs])
    assert (status, err) == (0, ""), err
    return [int(line) for line in out.split()]


ALL_NOISY = list(range(1, 39))
NOISE = [1, 34]


@pytest.mark.parametrize(("expression", "expected"), [
    # A bare field tests presence (tshark -Y vw3.crc_ok: 36 frames, !vw3.crc_ok: 1 34): frame 17's bad CRC
    # has a crc_ok, false. Before: "present and not false", 35 and 1 17 34.
    ("crc_ok", [n for n in ALL_NOISY if n not in NOISE]),
    ("not crc_ok", NOISE),
    ("!crc_ok", NOISE),
    ("crc_ok == 1", [n for n in ALL_NOISY if n not in (*NOISE, 17)]),
    ("crc_ok == 0", [17]),
    # The plugin adds vw3.unanswered and vw3.broadcast only where true (tshark -2 -Y vw3.unanswered: 28 29;
    # vw3.unanswered == 0 and vw3.broadcast: none)
    ("unanswered", [28, 29]),
    ("not unanswered", [n for n in ALL_NOISY if n not in (28, 29)]),
    ("unanswered == 0", []),
    ("broadcast", []),
    ("!broadcast", ALL_NOISY),
    ("broadcast == false", []),
])
def test_a_bare_field_tests_its_presence(expression: str, expected: list[int]) -> None:
    assert frames(expression, NOISY) == expected


def test_a_crc_typed_nowhere_is_no_crc_ok() -> None:
    typed = ["--hex", "0C 03 20 D0 00 03"]
    assert frames("crc_ok", *typed) == []
    assert frames("!crc_ok", *typed) == [1]
    assert frames("crc_typed == 0", *typed) == [1]
    assert frames("crc_ok", "--hex", "0C 03 20 D0 00 03 0E EE") == [1]  # a bad CRC typed: checked


def test_time_is_written_as_tshark_writes_frame_time_epoch() -> None:
    # tshark -r atv71_commissioning.pcap -c 3 -T fields -e frame.time_epoch -e frame.time_relative
    # -e vw3.response_time (before: 1767225600.00659 then 1767225600.052897)
    status, out, err = run_cli([ATV71, "-c", "3", "-T", "fields", "-e", "time", "-e", "time_relative",
                                "-e", "response_time"])
    assert (status, err) == (0, "")
    assert out == ("1767225600.006590000\t0.000000000\t\n"
                   "1767225600.017320000\t0.010730000\t0.010730000\n"
                   "1767225600.052897000\t0.046307000\t\n")
    assert run_cli(["--hex", "01 06 00 20 3F 00", "-T", "fields", "-e", "time", "-e", "frame"])[1] == "\t1\n"


# tshark -r noisy_bus.pcap -Y 'frame contains 0c:03' (items and pcap records are one to one there)
SLAVE_12 = [2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 30, 31, 35, 36]
NOT_SLAVE_12 = [n for n in ALL_NOISY if n not in SLAVE_12]


@pytest.mark.parametrize(("expression", "expected"), [
    # raw is the item's bytes, as tshark's frame: whole bytes, hex case ignored, slices. Before: the hex
    # text, so "0203" matched across nibbles, "c03" matched, "0C03" nothing, 0c:03 and raw[0:2] refused.
    ("raw contains 0c:03", SLAVE_12),
    ("raw contains 0C:03", SLAVE_12),
    ("raw contains 0c-03", SLAVE_12),
    ("raw contains 0c.03", SLAVE_12),
    ("raw contains 0c03", SLAVE_12),
    ("raw contains 0c", SLAVE_12),
    ("raw contains 1", [4, 5, 8, 9, 12, 13, 16, 17, 18, 19, 22, 23, 26, 27, 32, 33, 37, 38]),  # (01)
    ('raw contains "\\x0c\\x03"', SLAVE_12),  # a string: its characters' bytes
    ('raw contains "\\014"', SLAVE_12),
    ('raw contains "0c03"', []),  # (the characters 30 63 30 33, as tshark's)
    ('raw contains "c03"', []),
    ("raw[0:2] == 0c:03", SLAVE_12),
    ("raw[:2] == 0c:03", SLAVE_12),
    ("raw[0-1] == 0c:03", SLAVE_12),
    ("raw[0:2] === 0c:03", SLAVE_12),
    ("raw[0] == 0c", SLAVE_12),
    ("raw[0] == 12", []),  # (0x12)
    ("raw[1:2] == 03:00", [4, 8, 12, 16, 18, 22, 26, 28, 29, 32, 37]),
    ("raw[0:2] != 0c:03", NOT_SLAVE_12),
    ("raw[0:2] ~= 0c:03", NOT_SLAVE_12),
    ("raw == 0c:03", []),
    ("raw[0:2] >= 0c:03", [2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 30, 31, 34, 35, 36]),  # (34: fe e0)
    ("raw[0:2] > 0c", ALL_NOISY),  # longer is greater, as tshark orders bytes
    ("raw[0:1] < 0c:00", ALL_NOISY),
    ("raw[0:2] & 0f", ALL_NOISY[1:]),  # (frame 1: 00 ff, and over the shorter)
    ('raw matches "^\\x0c\\x03"', SLAVE_12),
    ("raw[0:2] contains 03", [n for n in ALL_NOISY if n not in (1, 34)]),
])
def test_raw_is_bytes_as_tsharks_frame(expression: str, expected: list[int]) -> None:
    assert frames(expression, NOISY) == expected


def test_raw_of_typed_bytes() -> None:
    typed = ["--hex", "01 06 00 20 3F 00"]
    assert frames('raw contains "0203"', *typed) == []  # (before: 1, "0203" across 00 20 3F)
    assert frames("raw contains 20:3f", *typed) == [1]
    assert frames("raw[2:2] == 00:20", *typed) == [1]
    assert frames("raw[-2:] == 99:f0", *typed) == [1]  # (the CRC computed: raw holds it)
    assert frames("raw[7] == f0", *typed) == [1]
    assert frames("raw[8] == f0", *typed) == []  # (past the end: no field)
    assert frames("raw[7:2] != f0", *typed) == []
    assert frames("raw[0:2,4] == 01:06:3f", *typed) == [1]


@pytest.mark.parametrize(("expression", "expected"), [
    # tshark 4.0.17 accepts === (all_eq) and !== (any_ne), \\x and octal escapes
    ("frame === 1", [1]),
    ("frame !== 1", ALL_NOISY[1:]),
    # a time takes decimals, not exponents (tshark refuses vw3.response_time >= 8.5e-3: accepted before)
    ("response_time >= 0.0085", [5, 7, 9, 13, 17, 19, 21, 27, 31, 33, 36, 38]),
    ("response_time >= 0.0135", []),
    ('function_name contains "Read\\x20Holding"', [n for n in ALL_NOISY if n not in (1, 34)]),
    ('function_name contains "Read\\040Holding"', [n for n in ALL_NOISY if n not in (1, 34)]),
    ("crc_ok && slave == 12", SLAVE_12),  # (before: `crc_ok is true or false, not 'slave'`)
    ("crc_ok || slave == 12", [n for n in ALL_NOISY if n not in (1, 34)]),
])
def test_wireshark_4_0_syntax(expression: str, expected: list[int]) -> None:
    assert frames(expression, NOISY) == expected


@pytest.mark.parametrize(("capture", "expression", "expected"), [
    # tshark -Y 'vw3.reg.value === 3' (all_eq) / '!== 3' (any_ne) ... with the plugin
    ("p38_protection.pcap", "value === 3", []),
    ("p38_protection.pcap", "value !== 3", [2, 4, 6, 8]),
    ("p38_protection.pcap", 'code === "CHCF"', []),  # (8400 has no code: one occurrence fewer, as there)
    ("atv71_commissioning.pcap", 'code === "CHCF"', [7, 8, 63, 103, 104]),
    ("atv71_commissioning.pcap", "value === 2", [7, 8]),
    ("atv71_commissioning.pcap", "value all_eq 2", [7, 8]),
])
def test_all_eq_and_any_ne_on_registers(capture: str, expression: str, expected: list[int]) -> None:
    assert frames(expression, str(ROOT / "captures" / capture)) == expected


@pytest.mark.parametrize(("expression", "message"), [
    # as tshark 4.0.17 refuses them
    ("frame == 1e0", "frame is a whole number, and 1e0 is not written as one (as tshark refuses it) "
     "(column 10)"),
    ("slave == 12.0", "slave is a whole number, and 12.0 is not written as one (as tshark refuses it) "
     "(column 10)"),
    ("fields.values contains 40",
     "contains needs a text or bytes field; fields.values is a number (column 15)"),
    ('fields.values contains "40"',
     "contains needs a text or bytes field; fields.values is a number (column 15)"),
    ("raw contains 0c0",
     "raw is a byte string: write its bytes in hex as 0c:03 (or 0c-03, 0c.03, 0c03), not '0c0' (column 14)"),
    ("raw[0] in {0c 05}", "in takes numbers or texts; raw is a byte string (tshark 4.0 refuses it too): "
     "compare with == or contains (column 8)"),
    ("slave[0] == 1", "slave is a number: only bytes (raw) and texts take a slice (column 6)"),
    ('notes contains "\\x"',
     "unknown escape \\x in a string (\\\" \\\\ \\n \\t \\xhh \\ooo ...) (column 17)"),
])
def test_refused_as_tshark_refuses(expression: str, message: str) -> None:
    status, out, err = run_cli(["-Y", expression, NOISY])
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == f"vw3-decode: {message}"


def test_fields_values_is_a_repeated_number() -> None:
    # fields.values == 40: one element is 40; === every element (tshark's all_eq)
    assert frames("fields.values == 40", ATV71) == [4]
    assert frames("fields.values === 40", ATV71) == []


def test_glossary_types_as_tshark_would() -> None:
    lines = run_cli(["-G", "fields"])[1].splitlines()
    assert "F\tLength\tlength\tFT_UINT32\tvw3\tBASE_DEC\t0x0\tbytes in the item" in lines  # (was FT_DOUBLE)
    assert "F\tRaw\traw\tFT_BYTES\tvw3\t\t0x0\tthe item's bytes, lowercase hex" in lines  # (was FT_STRING)
    assert ("F\tPDU values\tfields.values\tFT_UINT16\tvw3\tBASE_DEC\t0x0\tPDU key of functions 3 4 16 23 24"
            in lines)  # (was FT_NONE)


P38 = str(ROOT / "captures" / "p38_protection.pcap")


@pytest.mark.parametrize(("expression", "expected"), [
    # Neighbours, each as tshark 4.0.17 with the plugin selects on p38_protection.pcap (frames 4..12, where
    # the plugin knows the profile: its first three frames are provisional)
    ("slave == 014", list(range(1, 13))),  # octal, as Wireshark's (before: 14, no frame)
    ("slave == 0b1100", list(range(1, 13))),  # (before: refused)
    ("value & 0x8000 == 0x8000", [2, 4, 6, 8]),  # & then a comparison (before: refused)
    ("value & 0x8000 == 0", [2, 4, 6, 8]),  # (the 3 and 2 beside 16#8000)
    ('function_name > "Read"', list(range(1, 13))),  # ordering texts (before: "'Read' does not exist")
    ('function_name[0:4] == "Read"', list(range(1, 13))),  # a text's slice: its bytes (before: refused)
    ('code[0:2] == "CH"', [2, 4, 6, 8, 10, 12]),
    ('code[-1:] == "F"', [2, 4, 6, 8, 10, 12]),
    ('code[0:2] === "CH"', []),  # (COP)
])
def test_neighbours_as_wireshark(expression: str, expected: list[int]) -> None:
    assert frames(expression, P38) == expected


def test_a_leading_zero_with_8_or_9_is_refused() -> None:
    status, out, err = run_cli(["-Y", "slave == 019", P38])
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == ("vw3-decode: 019: a leading 0 is octal (as in Wireshark), and 8 and 9 "
                                   "are no octal digits (column 10)")
