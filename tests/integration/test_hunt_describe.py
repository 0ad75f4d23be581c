"""The hunt's Info texts (session 52), alike in vw3-decode (compiled engine and VW3_PURE_PYTHON=1) and the
plugin under real tshark 4.0: an FC24 answer of more values than a summary shows ends with how many more
(`… (+2)`, as register lists say it); an empty FIFO is `0 values`, no colon after it. FC43's object values
are ASCII as sent and every other byte `\\xNN` (objects 0..6 are ASCII strings, the private ones the
device's own: never read as Latin-1, `Ã©`), in the Info text, -V, --json and the plugin's tree. Limits the
spec sets on FC20, FC21 and a broadcast FC23 are warned of; no colon before the values of none."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare, lua_shown
from lua_harness import lua_items, python_items, write_pcap
from test_lua_info_data import T0, tshark, vw3_decode

pytestmark = pytest.mark.integration

RECORDS = [
    # the hunt's: pointer 1246, 10 values (8 shown)
    bytes.fromhex("11 18 04 de 07 87"),
    bytes.fromhex("11 18 00 16 00 0a 00 00 00 64 00 c8 01 2c 01 90 01 f4 02 58 02 bc 03 20 03 84 9e 09"),
    rtu("11 18 04de"), rtu("11 18 0002 0000"),  # an empty FIFO
    # FC43: VendorName `été ` in UTF-8; a private object 0x80 of two bytes
    rtu("11 2b 0e 01 00"), rtu("11 2b 0e 01 01 00 00 02 00 06 c3a974c3a920 80 02 abcd"),
]
FIFO, MEI = "Read FIFO Queue", "Encapsulated Interface Transport"
OBJECTS = r"VendorName='\xc3\xa9t\xc3\xa9 ' Object 128='\xab\xcd'"
INFO = [
    ("request", FIFO, "pointer 1246"),
    ("response", FIFO, "10 values: 0 100 200 300 400 500 600 700 … (+2)"),
    ("request", FIFO, "pointer 1246"),
    ("response", FIFO, "0 values"),
    ("request", MEI, "Read Device Identification, basic, from object 0"),
    ("response", MEI, f"Read Device Identification, basic: {OBJECTS}"),
]
TAILS = {1: " [#1, 1000.0 ms]", 3: " [#3, 1000.0 ms]", 5: " [#5, 1000.0 ms]"}


def _one_a_second(tmp_path_factory: pytest.TempPathFactory, name: str, records: list[bytes]) -> Path:
    return write_pcap(tmp_path_factory.mktemp(name) / f"{name}.pcap",
                      [(data, T0 + at) for at, data in enumerate(records)])


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _one_a_second(tmp_path_factory, "hunt_describe", RECORDS)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_info(capture: Path, pure: bool) -> None:
    assert vw3_decode(capture, pure).splitlines() == [
        f"{index + 1:>6} {index:>12.6f}  17 {kind:<9} {name} {info}{TAILS.get(index, '')}  CRC ok"
        for index, (kind, name, info) in enumerate(INFO)]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_objects(capture: Path, pure: bool) -> None:
    detail = vw3_decode(capture, pure, "-V").splitlines()
    assert [line.strip() for line in detail if line.startswith("        Object ")] == [
        r"Object 0 VendorName: '\xc3\xa9t\xc3\xa9 '", r"Object 128: '\xab\xcd'"]
    items = map(json.loads, vw3_decode(capture, pure, "--json").splitlines())
    (response,) = [item for item in items if item["frame"] == 6]
    assert response["objects"] == [{"id": 0, "name": "VendorName", "value": r"\xc3\xa9t\xc3\xa9 "},
                                   {"id": 128, "name": "Object 128", "value": r"\xab\xcd"}]


def test_plugin_info(capture: Path) -> None:
    assert tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines() == [
        f"17 {name} {kind} {info}" for kind, name, info in INFO]


def test_plugin_objects(capture: Path) -> None:
    values = tshark(capture, "-Y", "frame.number == 6", "-T", "fields", "-E", "occurrence=a",
                    "-E", "aggregator=|", "-e", "vw3.object.value")
    assert values.splitlines() == [r"\xc3\xa9t\xc3\xa9 |\xab\xcd"]


# The hunt's requests no limit warned of: FC20's byte count 0 (the spec's 0x07..0xF5), FC21's record of no
# word (and its byte count 7, the spec's 0x09..0xFB), FC23 broadcast (it reads: a broadcast only writes).
# (First, no colon before the values of none: `8401 (0)`.)
LIMIT_RECORDS = [rtu("11 10 20d1 0000 02 0005"), rtu("11 14 00"), rtu("11 15 07 06 0004 0007 0000"),
                 rtu("00 17 0001 0002 0003 0001 02 0007")]
LIMIT_LINES = [
    "Write Multiple Registers 8401 (0) [no response] [warning: quantity 0 outside the spec's 1..123] "
    "[warning: byte count 2 disagrees with the quantity 0] "
    "[warning: 2 bytes past the quantity 0, not written: 00 05]",
    "Read File Record 0 record group(s) [no response] [warning: byte count 0 outside the spec's 7..245]",
    "Write File Record 1 record group(s) [no response] [warning: byte count 7 outside the spec's 9..251] "
    "[warning: record 1's record length 0 outside the spec's 1..122]",
    "Read/Write Multiple Registers read 1..2 (2), write 3=7 [broadcast] "
    "[warning: Read/Write Multiple Registers cannot be broadcast (slave 0)]",
]


@pytest.fixture(scope="module")
def limits(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _one_a_second(tmp_path_factory, "hunt_limits", LIMIT_RECORDS)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_limits(limits: Path, pure: bool) -> None:
    slaves = [17, 17, 17, 0]
    assert vw3_decode(limits, pure).splitlines() == [
        f"{index + 1:>6} {index:>12.6f} {slaves[index]:>3} request   {line}  CRC ok"
        for index, line in enumerate(LIMIT_LINES)]


def test_plugin_limits(limits: Path) -> None:
    lua, _, _ = lua_items(limits)
    assert compare(python_items(limits), lua) == []
    assert [item.texts.get("warning") for item in lua_shown(lua)] == [
        ["quantity 0 outside the spec's 1..123", "byte count 2 disagrees with the quantity 0",
         "2 bytes past the quantity 0, not written: 00 05"],
        ["byte count 0 outside the spec's 7..245"],
        ["byte count 7 outside the spec's 9..251", "record 1's record length 0 outside the spec's 1..122"],
        ["Read/Write Multiple Registers cannot be broadcast (slave 0)"]]


def test_plugin_note_order_at_the_capture_end(tmp_path: Path) -> None:
    """An FC8 request the capture ends after: the end's note, then decoding's (pipeline.py pairs first)."""
    records = ["11 03 00 00 00 01 86 9a", "11 03 02 00 05 b9 84", "11 08 00 01 ff 00 f2 ab"]
    pcap = write_pcap(tmp_path / "fc8.pcap", [(bytes.fromhex(data), T0 + at) for at, data in enumerate(records)])
    notes = ["the capture ends before any response: not known whether it was answered",
             "clear the communications event log"]
    (request,) = [item for item in map(json.loads, vw3_decode(pcap, False, "--json").splitlines())
                  if item["frame"] == 3]
    assert request["notes"] == notes
    lua, _, _ = lua_items(pcap)
    assert compare(python_items(pcap), lua) == []
    assert lua_shown(lua)[2].texts.get("note") == notes
