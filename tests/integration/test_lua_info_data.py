"""The plugin's Info column says FC8's data and FC24's values as vw3-decode does: `0Bh Return Bus Message
Count = 300` (a word's value), ` data 0102…` (other data: its first 16 bytes, then `… (+2 bytes)`, `(+1 byte)`),
nothing for none, in request and answer; an FC24 answer its FIFO count and first 8 values (`3 values: 10 11
12`, `0 values`, `9 values: 1 2 3 4 5 6 7 8 … (+1)`), never its request's pointer; a frame whose fields do not
parse `(malformed)`; and FC5's coil, FC7's and FC12's status, FC11's counters, FC17's server id, FC20's and
FC21's record groups, FC22's masks, FC43's MEI as vw3-decode does, PLC style too, for a request met before
too. The tree's title says the same. vw3-decode -V names FC24's pointer as the spec does,
`FIFO pointer address` (its --json `start`, the plugin's vw3.start titled alike), and `FIFO count`; an FC8
sub-function nobody names is `unknown sub-function` in both. Real tshark 4.0 with -X lua_script:lua/vw3.lua
(-2 and one pass); vw3-decode under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

from dissector.codegen import fields_lua
from dissector.render import describe, detail

pytestmark = pytest.mark.integration

T0 = 1767225600.0  # 2026-01-01 00:00:00 UTC; one record a second
EIGHTEEN = "01 02 03 04 05 06 07 08 09 0a 0b 0c 0d 0e 0f 10 11 12"
RECORDS = [
    # the report's capture, as sent (CRC included)
    bytes.fromhex("01 08 00 0b 00 00 91 c9"), bytes.fromhex("01 08 00 0b 01 2c 91 84"),
    bytes.fromhex("01 18 00 10 80 13"), bytes.fromhex("01 18 00 08 00 03 00 0a 00 0b 00 0c 5a 67"),
    bytes.fromhex("01 08 00 0b 00 00 91 c9"), bytes.fromhex("01 08 00 02 00 00 41 cb"),
    # FC8 with no data, 18 bytes, 17 bytes, 4 bytes; a sub-function the spec does not define; 04 (no answer)
    rtu("01 08 0000"), rtu("01 08 0000"),
    rtu("01 08 0000" + EIGHTEEN), rtu("01 08 0000" + EIGHTEEN),
    rtu("01 08 0000" + EIGHTEEN[:-3]), rtu("01 08 0000" + EIGHTEEN[:-3]),
    rtu("01 08 0000 01020304"), rtu("01 08 0000 01020304"),
    rtu("01 08 0063 0000"), rtu("01 08 0063 0000"),
    rtu("01 08 0004 0000"),
    # FC24: an empty FIFO; 9 values (8 shown); a FIFO count past the values sent (malformed)
    rtu("01 18 0010"), rtu("01 18 0002 0000"),
    rtu("01 18 0010"), rtu("01 18 0014 0009 000100020003000400050006000700080009"),
    rtu("01 18 0010"), rtu("01 18 0006 0003 0001 0002"),
]
PLUS_TWO = "data 0102030405060708090a0b0c0d0e0f10… (+2 bytes)"
PLUS_ONE = "data 0102030405060708090a0b0c0d0e0f10… (+1 byte)"
INFO = [
    ("request", "Diagnostics 0Bh Return Bus Message Count = 0"),
    ("response", "Diagnostics 0Bh Return Bus Message Count = 300"),
    ("request", "Read FIFO Queue pointer 16"),
    ("response", "Read FIFO Queue 3 values: 10 11 12"),
    ("request", "Diagnostics 0Bh Return Bus Message Count = 0"),
    # (no echo of 0Bh: not its answer but the master's next request, as an FC8 answer echoes, 515aff6)
    ("request", "Diagnostics 02h Return Diagnostic Register = 0"),
    ("request", "Diagnostics 00h Return Query Data"),
    ("response", "Diagnostics 00h Return Query Data"),
    ("request", f"Diagnostics 00h Return Query Data {PLUS_TWO}"),
    ("response", f"Diagnostics 00h Return Query Data {PLUS_TWO}"),
    ("request", f"Diagnostics 00h Return Query Data {PLUS_ONE}"),
    ("response", f"Diagnostics 00h Return Query Data {PLUS_ONE}"),
    ("request", "Diagnostics 00h Return Query Data data 01020304"),
    ("response", "Diagnostics 00h Return Query Data data 01020304"),
    ("request", "Diagnostics 63h unknown sub-function = 0"),
    ("response", "Diagnostics 63h unknown sub-function = 0"),
    ("request", "Diagnostics 04h Force Listen Only Mode = 0"),
    ("request", "Read FIFO Queue pointer 16"),
    ("response", "Read FIFO Queue 0 values"),
    ("request", "Read FIFO Queue pointer 16"),
    ("response", "Read FIFO Queue 9 values: 1 2 3 4 5 6 7 8 … (+1)"),
    ("request", "Read FIFO Queue pointer 16"),
    ("response", "Read FIFO Queue (malformed)"),
]
ODD = " [warning: diagnostic data is not a whole number of words]"
UNKNOWN = " [warning: diagnostic sub-function 99 is not defined by the spec]"
# vw3-decode's tails of the frames that have one (by index), after `[#n, 1000.0 ms]` for an answer
TAILS = {
    4: " [no response]", 5: " [no response]",
    10: ODD, 11: ODD, 14: UNKNOWN, 15: UNKNOWN, 16: " [no response expected: the spec's server returns none]",
    # (the FC24 answers after the 08/04 show the slave did not take Listen Only Mode: pairing.py _heard)
    18: " [slave 1 answers: it is not in listen-only mode (#17, 08/04)]",
    22: " [warning: malformed response: fifo_count past the end]",
}
ANSWERS = {1: 1, 3: 3, 7: 7, 9: 9, 11: 11, 13: 13, 15: 15, 18: 18, 20: 20, 22: 22}  # index: its request's frame


def vw3_decode_line(index: int) -> str:
    kind, info = INFO[index]
    link = f" [#{ANSWERS[index]}, 1000.0 ms]" if index in ANSWERS else ""
    return f"{index + 1:>6} {index:>12.6f}   1 {kind:<9} {info}{link}{TAILS.get(index, '')}  CRC ok"


def plugin_line(kind: str, info: str) -> str:
    """The plugin's Info of vw3-decode's: the slave first, the kind after the function's name."""
    name = "Read FIFO Queue" if info.startswith("Read FIFO Queue") else "Diagnostics"
    return f"1 {name} {kind} {info[len(name) + 1:]}"


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("info_data") / "info.pcap",
                      [(data, T0 + at) for at, data in enumerate(RECORDS)])


def vw3_decode(pcap: Path, pure: bool, *args: str) -> str:
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    else:  # a missing engine would run the Python stages twice
        from dissector.accel import fastsummary
        assert fastsummary.available() and fastsummary.built(), "the compiled engine is not built"
    result = subprocess.run([sys.executable, "-m", "dissector", str(pcap), *args], capture_output=True, text=True,
                            env=env, cwd=ROOT, timeout=300)
    assert (result.returncode, result.stderr) == (0, "")
    return result.stdout


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_info(capture: Path, pure: bool) -> None:
    assert vw3_decode(capture, pure).splitlines() == [vw3_decode_line(index) for index in range(len(INFO))]


def test_plugin_info_two_pass(capture: Path) -> None:
    lines = tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines()
    assert lines == [plugin_line(kind, info) for kind, info in INFO]
    # spelled out, the report's four
    assert lines[:4] == ["1 Diagnostics request 0Bh Return Bus Message Count = 0",
                         "1 Diagnostics response 0Bh Return Bus Message Count = 300",
                         "1 Read FIFO Queue request pointer 16",
                         "1 Read FIFO Queue response 3 values: 10 11 12"]


def test_plugin_info_one_pass(capture: Path) -> None:
    # (one pass: every slave's device is still provisional, and the framer decides a frame with the next
    # record's bytes: the first six records, each one frame, say the same as -2)
    lines = tshark(capture, "-T", "fields", "-e", "_ws.col.Info", two_pass=False).splitlines()
    assert lines[:6] == [line + " [provisional]" for line in
                         tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines()[:6]]


def test_plugin_tree_title(capture: Path) -> None:
    out = tshark(capture, "-V", "-Y", "frame.number == 2 || frame.number == 4 || frame.number == 23")
    titles = [line for line in out.splitlines() if line.startswith("VW3 Modbus")]
    assert titles == ["VW3 Modbus RTU, 1 Diagnostics response 0Bh Return Bus Message Count = 300",
                      "VW3 Modbus RTU, 1 Read FIFO Queue response 3 values: 10 11 12",
                      "VW3 Modbus RTU, 1 Read FIFO Queue response (malformed)"]


def _ascii(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([-sum(body) & 0xFF])).hex().upper().encode() + b"\r\n"


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_ascii_frames_say_the_same(tmp_path: Path, pure: bool) -> None:
    frames = ["0108000B012C", "0108000B012C", "01180010", "011800080003000A000B000C",
              "01080000" + EIGHTEEN.replace(" ", "")]
    assert _ascii("01180010") == b":01180010D7\r\n"  # (the LRC: minus the bytes' sum, Modbus over Serial Line 6.2.1)
    pcap = write_pcap(tmp_path / "ascii.pcap", [(_ascii(frame), T0 + at) for at, frame in enumerate(frames)])
    assert tshark(pcap, "-T", "fields", "-e", "_ws.col.Info").splitlines() == [
        "1 Diagnostics request 0Bh Return Bus Message Count = 300",
        "1 Diagnostics response 0Bh Return Bus Message Count = 300",
        "1 Read FIFO Queue request pointer 16",
        "1 Read FIFO Queue response 3 values: 10 11 12",
        f"1 Diagnostics request 00h Return Query Data {PLUS_TWO}"]
    assert [line[34:] for line in vw3_decode(pcap, pure).splitlines()] == [
        # (the counters take data 0000: data/modbus.toml [diagnostic_data], tests/unit/test_fc8_request_data.py)
        "Diagnostics 0Bh Return Bus Message Count = 300 [warning: diagnostic data 012C is not what sub-function 0Bh"
        " takes (0000): a server answers exception 03]  LRC ok",
        "Diagnostics 0Bh Return Bus Message Count = 300 [#1, 1000.0 ms]  LRC ok",
        "Read FIFO Queue pointer 16  LRC ok",
        "Read FIFO Queue 3 values: 10 11 12 [#3, 1000.0 ms]  LRC ok",
        f"Diagnostics 00h Return Query Data {PLUS_TWO} [the capture ends before any response: not known whether it was "
        "answered]  LRC ok"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_fc24_pointer_named_alike(capture: Path, pure: bool) -> None:
    text = vw3_decode(capture, pure, "-V")
    frames = {block.split(":", 1)[0]: block for block in ("\n" + text).split("\nFrame ")[1:]}
    assert "\n        Function: 24 (0x18) Read FIFO Queue\n        FIFO pointer address: 16 (0x10)\n" \
           "        CRC: 0x1380 [CRC ok]\n" in frames["3"]
    assert "\n        Byte count: 8 (0x8)\n        FIFO count: 3 (0x3)\n        Values (3)\n" in frames["4"]
    assert "\n        Sub-function name: unknown sub-function\n" in frames["15"]
    rows = [json.loads(line) for line in vw3_decode(capture, pure, "--json").splitlines()]
    assert (rows[2]["start"], rows[2]["fields"], rows[3]["start"]) == (16, {"address": 16}, 16)
    # the plugin: the same value in vw3.start, titled as -V labels it (the answer's from its request)
    tree = tshark(capture, "-V", "-Y", "frame.number == 3 || frame.number == 4")
    assert [line for line in tree.splitlines() if "pointer address" in line] == [
        "    FIFO pointer address: 16", "    [FIFO pointer address: 16]"]
    # (of the frames that parse: the plugin gives the malformed answer no start, vw3-decode its request's)
    starts = tshark(capture, "-Y", "vw3.function == 24 && !vw3.warning", "-T", "fields", "-e", "vw3.start").split()
    assert starts == [str(row["start"]) for row in rows if row["function"] == 24 and not row["warnings"]] == ["16"] * 7


def test_the_plugin_takes_vw3_decode_words() -> None:
    # (codegen/fields_lua.py: -V's label of FC24's pointer, and the unknown sub-function's text)
    words = fields_lua.plugin_fields()
    assert words["start_words"] == {24: {"title": "FIFO pointer address"}}
    assert words["info"]["unknown_subfunction"] == describe.UNKNOWN_SUBFUNCTION == "unknown sub-function"
    assert (words["info"]["forms"]["request"][8], words["info"]["forms"]["response"][24]) == ("diagnostics", "fifo")
    assert detail.field_label("address", 24) == "FIFO pointer address"
    assert (detail.field_label("address", 6), detail.field_label("fifo_count"), detail.field_label("mei_type"),
            detail.field_label("byte_count")) == ("Address", "FIFO count", "MEI type", "Byte count")


# The other forms the plugin now says as vw3-decode does (describe.TEXT_FORMS and _BY_NAME): FC5's coil,
# FC7's and FC12's status, FC11's counters, FC17's server id, FC20's and FC21's record groups, FC22's masks,
# FC43's MEI; each request twice (the second a request met before: its text kept, lua/src/records.lua known_requests).
OTHERS = [
    (rtu("01 05 0003 FF00"), "Write Single Coil", "request", "3 = ON", "00004 = ON"),
    (rtu("01 05 0003 FF00"), "Write Single Coil", "response", "3 = ON", "00004 = ON"),
    (rtu("01 05 0004 1234"), "Write Single Coil", "request", "4 = 0x1234", "00005 = 0x1234"),
    (rtu("01 05 0004 1234"), "Write Single Coil", "response", "4 = 0x1234", "00005 = 0x1234"),
    (rtu("01 16 0004 00F2 0025"), "Mask Write Register", "request", "4 AND 0x00F2 OR 0x0025", None),
    (rtu("01 16 0004 00F2 0025"), "Mask Write Register", "response", "4 AND 0x00F2 OR 0x0025", None),
    (rtu("01 07"), "Read Exception Status", "request", "", None),
    (rtu("01 07 6D"), "Read Exception Status", "response", "status 0x6D", None),
    (rtu("01 0B"), "Get Comm Event Counter", "request", "", None),
    (rtu("01 0B FFFF 0108"), "Get Comm Event Counter", "response", "status 0xFFFF, 264 events", None),
    (rtu("01 0C"), "Get Comm Event Log", "request", "", None),
    (rtu("01 0C 08 0000 0108 0121 2000"), "Get Comm Event Log", "response", "status 0x0000, 264 events, 289 messages", None),
    (rtu("01 11"), "Report Server ID", "request", "", None),
    (rtu("01 11 06 01 FF 41 42 43 44"), "Report Server ID", "response", "server id 1, run ON, 'ABCD'", None),
    (rtu("01 11"), "Report Server ID", "request", "", None),
    (rtu("01 11 04 12 00 0A 0B"), "Report Server ID", "response", "server id 18, run OFF, 2 bytes", None),
    (rtu("01 14 0E 06 0004 0001 0002 06 0003 0009 0002"), "Read File Record", "request", "2 record group(s)", None),
    (rtu("01 14 0C 05 06 0DFE 0020 05 06 33CD 0040"), "Read File Record", "response", "2 record group(s)", None),
    (rtu("01 15 0D 06 0004 0007 0003 06AF 04BE 100D"), "Write File Record", "request", "1 record group(s)", None),
    (rtu("01 15 0D 06 0004 0007 0003 06AF 04BE 100D"), "Write File Record", "response", "1 record group(s)", None),
    (rtu("01 2B 0E 01 00"), "Encapsulated Interface Transport", "request",
     "Read Device Identification, basic, from object 0", None),
    (rtu("01 2B 0E 01 01 00 00 03 00 03 41 42 43 01 02 58 59 02 04 31 30 30 30"), "Encapsulated Interface Transport",
     "response", "Read Device Identification, basic: VendorName='ABC' ProductCode='XY' MajorMinorRevision='1000'", None),
    (rtu("01 2B 0D 01 02 03"), "Encapsulated Interface Transport", "request", "CANopen General Reference", None),
    (rtu("01 2B 0D 0A 0B"), "Encapsulated Interface Transport", "response", "CANopen General Reference", None),
    (rtu("01 2B 05 01"), "Encapsulated Interface Transport", "request", "MEI 5", None),
    (rtu("01 2B 05 01"), "Encapsulated Interface Transport", "response", "MEI 5", None),
]
TWICE = OTHERS[:6] + OTHERS[:6] + OTHERS[16:22] + OTHERS[16:22]


def _others(plc: bool, rows: list[tuple[bytes, str, str, str, str | None]]) -> list[tuple[str, str, str]]:
    return [(kind, name, (plc and in_plc or info)) for _data, name, kind, info, in_plc in rows]


@pytest.mark.parametrize("plc", [False, True], ids=["protocol", "plc"])
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_other_codes_in_vw3_decode(tmp_path: Path, plc: bool, pure: bool) -> None:
    pcap = write_pcap(tmp_path / "others.pcap", [(data, T0 + at) for at, (data, *_rest) in enumerate(OTHERS)])
    lines = vw3_decode(pcap, pure, "--address-style", "plc" if plc else "protocol").splitlines()
    assert [line[24:34].rstrip() for line in lines] == [kind for _d, _n, kind, _i, _p in OTHERS]
    # (the Info: what comes before the tail's first `[...]` and the CRC's words)
    assert [re.split(r" \[|  CRC ok", line[34:])[0] for line in lines] == [
        f"{name} {info}".rstrip() for _kind, name, info in _others(plc, OTHERS)]


@pytest.mark.parametrize("plc", [False, True], ids=["protocol", "plc"])
@pytest.mark.parametrize("rows", ["once", "twice"])
def test_other_codes_in_the_plugin(tmp_path: Path, plc: bool, rows: str) -> None:
    chosen = OTHERS if rows == "once" else TWICE
    pcap = write_pcap(tmp_path / "others.pcap", [(data, T0 + at) for at, (data, *_rest) in enumerate(chosen)])
    # (a settled profile: the requests met before are kept with their Info text, the quick lanes take them)
    style = ["-o", "vw3.address_style:plc"] if plc else []
    expected = [f"1 {name} {kind} {info}".rstrip() for kind, name, info in _others(plc, chosen)]
    def info(two_pass: bool) -> list[str]:
        return tshark(pcap, *style, "-o", "vw3.profiles:generic", "-T", "fields", "-e", "_ws.col.Info",
                      two_pass=two_pass).splitlines()

    assert info(True) == expected
    # (one pass: an FC43 of another MEI type has no length of its own, framed with the next record's bytes)
    assert info(False)[:22] == expected[:22]
