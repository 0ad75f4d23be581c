"""The plugin shows every field of a PDU that vw3-decode -V lists (data/fields.toml `pdu`, lua/src/tree.lua
add_pdu), for every public function code, with filterable vw3.* fields: FC7's status, FC8's data, FC11's
and FC12's counters, FC12's events, FC20's sub-requests and sub-responses, FC21's records, FC22's masks,
FC23's write window, FC24's FIFO count and values, FC43's MEI type and device-id header, FC1/FC15's packed
status. FC8's Info column names the sub-function and its data as vw3-decode's summary does (`= 300`); FC24's
request says what it is, a FIFO pointer address (`pointer 1246`), never a window of registers (`1246..1248`),
its answer its values (`3 values: 1 2 3`), in the plugin and in
vw3-decode --json alike (no `quantity`: the FIFO count is the PDU field fifo_count). Real tshark with
-X lua_script:lua/vw3.lua; vw3-decode under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

from dissector.codegen import fields_lua
from dissector.errors import GenerateError
from dissector.protocol.crc import with_crc

pytestmark = pytest.mark.integration

# Request and answer of each function code, one record each, 10 ms apart.
FRAMES = [
    "0107", "01076D", "0108000B0000", "0108000B012C", "010B", "010BFFFF0108",
    "010C", "010C080000010801212000", "0111", "01110601FF41424344",
    "01140E0600040001000206000300090002", "01140C05060DFE0020050633CD0040",
    "01150D0600040007000306AF04BE100D", "01150D0600040007000306AF04BE100D",
    "0116000400F20025", "0116000400F20025", "011804DE", "011800080003000100020003",
    "012B0E0100", "012B0E0101000003000341424301025859020431303030",
    "012B0D010203", "012B0D0A0B", "010F0000000A02FF03", "010F0000000A",
    "011700030006000E00030600FF00FF00FF", "01170C00FE0ACD00010003000D00FF", "010300000002", "018302",
]
T0 = 1700000000.0

# Per frame: its tree's title (the Info text) and its lines but those every frame has (item, kind, offset,
# mode, slave, function, profile, CRC, links), as tshark -V prints them.
TREES: list[tuple[str, list[str]]] = [
    ("VW3 Modbus RTU, 1 Read Exception Status request", []),
    ("VW3 Modbus RTU, 1 Read Exception Status response status 0x6D", ["    Status: 109 (0x6d)"]),
    ("VW3 Modbus RTU, 1 Diagnostics request 0Bh Return Bus Message Count = 0", [
        "    Sub-function: Return Bus Message Count (11)", "    Data: 0000",
        "    [Sub-function name: Return Bus Message Count]"]),
    ("VW3 Modbus RTU, 1 Diagnostics response 0Bh Return Bus Message Count = 300", [
        "    Sub-function: Return Bus Message Count (11)", "    Data: 012c",
        "    [Sub-function name: Return Bus Message Count]"]),
    ("VW3 Modbus RTU, 1 Get Comm Event Counter request", []),
    ("VW3 Modbus RTU, 1 Get Comm Event Counter response status 0xFFFF, 264 events", ["    Status: 65535 (0xffff)", "    Event count: 264"]),
    ("VW3 Modbus RTU, 1 Get Comm Event Log request", []),
    ("VW3 Modbus RTU, 1 Get Comm Event Log response status 0x0000, 264 events, 289 messages", [
        "    Byte count: 8", "    Status: 0 (0x0000)", "    Event count: 264", "    Message count: 289",
        "    Events: 2000", "    Event list (2)", "        [0]", "            Byte: 32 (0x20)",
        "            Event: Unknown Event", "        [1]", "            Byte: 0 (0x0)",
        "            Event: Initiated Communication Restart"]),
    ("VW3 Modbus RTU, 1 Report Server ID request", []),
    ("VW3 Modbus RTU, 1 Report Server ID response server id 1, run ON, 'ABCD'", [
        "    Byte count: 6", "    Server id: 1 (0x01)", "    Run indicator: ON (0xff)", "    Additional data: ABCD"]),
    ("VW3 Modbus RTU, 1 Read File Record request 2 record group(s)", [
        "    Byte count: 14",
        "    Sub-request", "        Reference type: 6", "        File: 4", "        Record: 1", "        Length: 2",
        "    Sub-request", "        Reference type: 6", "        File: 3", "        Record: 9", "        Length: 2"]),
    ("VW3 Modbus RTU, 1 Read File Record response 2 record group(s)", [
        "    Byte count: 12",
        "    Sub-response", "        Length: 5", "        Reference type: 6", "        Value: 3582 (0x0dfe)",
        "        Value: 32 (0x0020)",
        "    Sub-response", "        Length: 5", "        Reference type: 6", "        Value: 13261 (0x33cd)",
        "        Value: 64 (0x0040)"]),
] + [
    (f"VW3 Modbus RTU, 1 Write File Record {kind} 1 record group(s)", [
        "    Byte count: 13", "    Record written", "        Reference type: 6", "        File: 4",
        "        Record: 7", "        Length: 3", "        Value: 1711 (0x06af)", "        Value: 1214 (0x04be)",
        "        Value: 4109 (0x100d)"]) for kind in ("request", "response")
] + [
    (f"VW3 Modbus RTU, 1 Mask Write Register {kind} 4 AND 0x00F2 OR 0x0025", [
        "    Address: 4", "    [Quantity: 1]", "    AND mask: 242 (0x00f2)", "    OR mask: 37 (0x0025)",
        # (its register, as vw3-decode --json lists it: render/registers.py mask_register)
        "    Register 4: AND 0x00F2 OR 0x0025: the result depends on the value before", "        [Address: 4]",
        "        [Meaning: AND 0x00F2 OR 0x0025: the result depends on the value before]"])
    for kind in ("request", "response")
] + [
    ("VW3 Modbus RTU, 1 Read FIFO Queue request pointer 1246", ["    FIFO pointer address: 1246"]),
    ("VW3 Modbus RTU, 1 Read FIFO Queue response 3 values: 1 2 3", [
        "    [FIFO pointer address: 1246]", "    Byte count: 8", "    FIFO count: 3", "    FIFO value: 1 (0x0001)",
        "    FIFO value: 2 (0x0002)", "    FIFO value: 3 (0x0003)"]),
    ("VW3 Modbus RTU, 1 Encapsulated Interface Transport request Read Device Identification, basic, from object 0", [
        "    MEI type: Read Device Identification (14)", "    Read code: basic (1)", "    Object id: 0"]),
    ("VW3 Modbus RTU, 1 Encapsulated Interface Transport response Read Device Identification, basic: "
     "VendorName='ABC' ProductCode='XY' MajorMinorRevision='1000'", [
        "    MEI type: Read Device Identification (14)", "    Read code: basic (1)",
        "    Conformity: basic, stream access only (1)",
        "    More follows: 0 (0x00)", "    Next object id: 0", "    Object count: 3",
        "    VendorName: 'ABC'", "        Object id: 0", "        [Name: VendorName]", "        Value: ABC",
        "    ProductCode: 'XY'", "        Object id: 1", "        [Name: ProductCode]", "        Value: XY",
        "    MajorMinorRevision: '1000'", "        Object id: 2", "        [Name: MajorMinorRevision]",
        "        Value: 1000"]),
    ("VW3 Modbus RTU, 1 Encapsulated Interface Transport request CANopen General Reference", [
        "    MEI type: CANopen General Reference (13)", "    Data: 010203"]),
    ("VW3 Modbus RTU, 1 Encapsulated Interface Transport response CANopen General Reference", [
        "    MEI type: CANopen General Reference (13)", "    Data: 0a0b"]),
    ("VW3 Modbus RTU, 1 Write Multiple Coils request 0..9 (10)", [
        "    Start address: 0", "    Quantity: 10", "    Byte count: 2", "    Status: ff03",
        *[line for bit in range(10)
          for line in (f"    Bit {bit} = 1", f"        [Address: {bit}]", "        [Value: 1]")]]),
    ("VW3 Modbus RTU, 1 Write Multiple Coils response 0..9 (10) written", ["    Start address: 0", "    Quantity: 10"]),
]
TREES += [
    ("VW3 Modbus RTU, 1 Read/Write Multiple Registers request read 3..8 (6), write 14..16 (3)", [
        "    Read start: 3", "    Read quantity: 6", "    Write start: 14", "    Write quantity: 3",
        "    Byte count: 6",
        *[line for address in (14, 15, 16) for line in (
            f"    Register {address} = 255", f"        [Address: {address}]", "        Value: 255 (0x00ff)")]]),
    ("VW3 Modbus RTU, 1 Read/Write Multiple Registers response 3..8 (6)", [
        "    [Start address: 3]", "    [Quantity: 6]", "    Byte count: 12",
        *[line for address, value in ((3, 254), (4, 2765), (5, 1), (6, 3), (7, 13), (8, 255)) for line in (
            f"    Register {address} = {value}", f"        [Address: {address}]",
            f"        Value: {value} (0x{value:04x})")]]),
    ("VW3 Modbus RTU, 1 Read Holding Registers request 0..1 (2)", ["    Start address: 0", "    Quantity: 2"]),
    ("VW3 Modbus RTU, 1 Read Holding Registers exception 2 (Illegal Data Address)", [
        "    Exception code: Illegal Data Address (2)",
        "    [Expert Info (Note/Response): Exception 2: Illegal Data Address]",
        "        [Exception 2: Illegal Data Address]", "        [Severity level: Note]", "        [Group: Response]",
        "    [Exception name: Illegal Data Address]"]),
]

# The lines every frame's tree has, left out of TREES.
_COMMON = re.compile(r"^    \[?(Item|Kind|Stream offset|Mode|Slave|Function|Function name|Device profile|Profile|CRC|"
                     r"Expected CRC|CRC OK|Request in frame|Response in frame|Time since request)[:\]]")


def _trees(text: str) -> list[tuple[str, list[str]]]:
    out: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("VW3 "):
            out.append((line, []))
        elif out and line.startswith("    ") and not line.startswith("        ") or out and line.startswith("        "):
            if not _COMMON.match(line):
                out[-1][1].append(line)
        elif line and not line.startswith(" "):
            out.append(("", []))  # (another protocol's tree ends the frame's)
    return [tree for tree in out if tree[0]]


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    records = [(with_crc(bytes.fromhex(text)), T0 + 0.01 * index) for index, text in enumerate(FRAMES)]
    return write_pcap(tmp_path_factory.mktemp("pdu_fields") / "pdu.pcap", records)


def _tshark(pcap: Path, *args: str) -> str:
    result = run_tshark(pcap, *args)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


def test_plugin_tree_shows_every_pdu_field(capture: Path) -> None:
    trees = _trees(_tshark(capture, "-V"))
    assert [title for title, _ in trees] == [title for title, _ in TREES]
    for (title, lines), (_, expected) in zip(trees, TREES):
        assert lines == expected, title


def test_pdu_fields_filter_and_print(capture: Path) -> None:
    def frames(expression: str) -> list[str]:
        return _tshark(capture, "-Y", expression, "-T", "fields", "-e", "frame.number").split()

    assert frames("vw3.status == 0x6d") == ["2"]
    assert frames("vw3.event_count == 264") == ["6", "8"]
    assert frames("vw3.and_mask == 0xf2 && vw3.or_mask == 0x25") == ["15", "16"]
    assert frames("vw3.fifo_count == 3") == ["18"]
    assert frames("vw3.file.record == 9") == ["11"]
    assert frames("vw3.data == 01:2c") == ["4"]
    assert frames("vw3.mei.object_count == 3") == ["20"]
    assert frames("vw3.write_start == 14") == ["25"]
    # FC24: the FIFO pointer is vw3.start (vw3-decode's `start`), the FIFO count no vw3.quantity
    assert frames("vw3.start == 1246") == ["17", "18"]
    assert frames("vw3.quantity && vw3.function == 24") == []
    values = _tshark(capture, "-Y", "vw3.fifo_count", "-T", "fields", "-e", "vw3.fifo_value", "-e", "vw3.fifo_count")
    assert values.splitlines() == ["1,2,3\t3"]


def test_info_column_names_fc8_sub_function_and_fc24_pointer(capture: Path) -> None:
    info = _tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines()
    # (as vw3-decode's Info: FC8's data after the sub-function, FC24's answer its values, not its request's pointer)
    assert info[2:4] == ["1 Diagnostics request 0Bh Return Bus Message Count = 0",
                         "1 Diagnostics response 0Bh Return Bus Message Count = 300"]
    assert info[16:18] == ["1 Read FIFO Queue request pointer 1246", "1 Read FIFO Queue response 3 values: 1 2 3"]
    # one pass (Wireshark opening the file) says the same
    one = run_tshark(capture, "-T", "fields", "-e", "_ws.col.Info", two_pass=False)
    assert one.stdout.splitlines()[16:18] == info[16:18]


# vw3-decode's FC24 pair: the pointer address as `start` (the answer's from its request), the FIFO count and
# values as its fields, no `quantity` (it read 1246..1248 as a window of registers).
FIFO_JSON = [
    {"frame": 1, "kind": "request", "offset": 0, "length": 6, "time": T0, "raw": "011804de0347", "mode": "rtu",
     "slave": 1, "function": 24, "function_name": "Read FIFO Queue", "crc_ok": True, "crc": 18179,
     "crc_expected": 18179, "broadcast": False, "start": 1246, "profile": "generic", "response_frame": 2, "unanswered": False,
     "fields": {"address": 1246}, "warnings": [], "notes": []},
    {"frame": 2, "kind": "response", "offset": 6, "length": 14, "time": T0 + 0.01,
     "raw": "0118000800030001000200036fa0", "mode": "rtu", "slave": 1, "function": 24, "function_name": "Read FIFO Queue", "crc_ok": True, "crc": 41071,
     "crc_expected": 41071, "broadcast": False, "start": 1246, "profile": "generic", "request_frame": 1, "response_time": 0.01,
     "fields": {"byte_count": 8, "fifo_count": 3, "values": [1, 2, 3]}, "warnings": [], "notes": []},
]
FIFO_SUMMARY = [
    "     1     0.000000   1 request   Read FIFO Queue pointer 1246  CRC ok",
    "     2     0.010000   1 response  Read FIFO Queue 3 values: 1 2 3 [#1, 10.0 ms]  CRC ok",
]
FIFO_DETAIL = """Frame 2: 14 bytes at offset 6, response (RTU)
    Arrival time: 2023-11-14 22:13:20.010000 UTC (0.010000 s since the first item)
    Modbus RTU
        Slave: 1
        Function: 24 (0x18) Read FIFO Queue
        [FIFO pointer address: 1246]
        Byte count: 8 (0x8)
        FIFO count: 3 (0x3)
        Values (3)
            [0]: 1 (0x0001)
            [1]: 2 (0x0002)
            [2]: 3 (0x0003)
        CRC: 0xA06F [CRC ok]
    Request in frame: 1
    Response time: 10.000 ms"""


@pytest.mark.parametrize("pure", ["", "1"], ids=["engine", "pure-python"])
def test_vw3_decode_fc24_says_pointer_count_and_values(tmp_path: Path, pure: str) -> None:
    pcap = write_pcap(tmp_path / "fifo.pcap", [(with_crc(bytes.fromhex(FRAMES[16])), T0),
                                                (with_crc(bytes.fromhex(FRAMES[17])), T0 + 0.01)])
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    if pure:
        env["VW3_PURE_PYTHON"] = pure
    else:  # a missing engine would run the Python stages twice
        from dissector.accel import fastsummary

        assert fastsummary.available() and fastsummary.built(), "the compiled engine is not built"

    def run(*args: str) -> str:
        result = subprocess.run([sys.executable, "-m", "dissector", str(pcap), *args], capture_output=True,
                                text=True, env=env, cwd=ROOT, timeout=300)
        assert result.returncode == 0, result.stderr
        return result.stdout

    rows = [json.loads(line) for line in run("--json").splitlines()]
    assert [{**row, "response_time": round(row["response_time"], 6)} if "response_time" in row else row
            for row in rows] == FIFO_JSON
    assert run().splitlines() == FIFO_SUMMARY
    assert FIFO_DETAIL in run("-V")


def test_every_layout_field_has_its_plugin_field(monkeypatch: pytest.MonkeyPatch) -> None:
    """codegen fails on a PDU field no plugin field shows (a layout field added to data/modbus.toml only)."""
    shown = fields_lua.pdu_fields()
    assert shown["fifo_response.values"] == ["fifo_value"] and shown["mask_write.or_mask"] == ["or_mask"]
    assert shown["report_server_id_response.additional_data"] == ["additional_data", "additional_bytes"]
    catalogue = fields_lua._pdu_catalogue()
    for entry in catalogue["field"]:
        if entry.get("filter") == "vw3.fifo_count":
            del entry["pdu"]
    monkeypatch.setattr(fields_lua, "_pdu_catalogue", lambda: catalogue)
    with pytest.raises(GenerateError, match="fifo_response.fifo_count: no field shows it"):
        fields_lua.pdu_fields()
