"""A Report Server ID (FC17) answer whose server id is longer than one byte (the spec leaves its length to the
device, Application Protocol 6.17: server id, run indicator 00 OFF / FF ON, additional data). pymodbus 3.x
answers `09 'Pymodbus' FF` (its ReportDeviceIdResponse: the identifier, the run indicator last). When the
byte after a one-byte id is no run indicator and a later one is, every engine reads the id up to the first
00 or FF after its first byte (as text where printable, else its bytes), with a warning giving that length:
`server id 'Pymodbus', run ON`. Before, all showed the one-byte reading's wrong split, `server id 80, run 121,
7 bytes` (-V `Server id: 80`, `Run indicator: Unknown (0x79)`, --json `"server_id": 80`) beside a warning that
the id was probably longer. Oracle: pymodbus's own decoder (identifier, status) for its answers. Wireshark
4.0 shows FC17's data as bytes only (Modbus/TCP `Data: 0950796d6f64627573ff`, mbrtu nothing).
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("05 11"), rtu("05 11 09 50 79 6D 6F 64 62 75 73 FF"),  # pymodbus: 'Pymodbus', then ON
          rtu("05 11"), rtu("05 11 05 01 02 00 41 42"),  # a two-byte id 01 02, then OFF, 'AB'
          rtu("05 11"), rtu("05 11 08 12 34 56 78 9A BC FF 07")]  # six bytes, ON, one more byte
LONGER = ("server id of {} bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte id, "
          "0x{:02X} is no run indicator")
WARNINGS = [[], [LONGER.format(8, 0x79)], [], [LONGER.format(2, 0x02)], [], [LONGER.format(6, 0x34)]]
LINES = [
    f"     2            -   5 response  Report Server ID server id 'Pymodbus', run ON, 0 bytes [#1] "
    f"[warning: {WARNINGS[1][0]}]  CRC ok",
    f"     4            -   5 response  Report Server ID server id 01 02, run OFF, 'AB' [#3] "
    f"[warning: {WARNINGS[3][0]}]  CRC ok",
    f"     6            -   5 response  Report Server ID server id 12 34 56 78 9A BC, run ON, 1 byte [#5] "
    f"[warning: {WARNINGS[5][0]}]  CRC ok",
]
# --json fields (a longer id as additional data is given: text where printable, else hex)
FIELDS = [
    {"byte_count": 9, "server_id": "Pymodbus", "run_indicator": "ON", "additional_data": ""},
    {"byte_count": 5, "server_id": "0102", "run_indicator": "OFF", "additional_data": "AB"},
    {"byte_count": 8, "server_id": "123456789abc", "run_indicator": "ON", "additional_data": "07"},
]
TREES = [  # -V, from the byte count to the CRC
    "        Byte count: 9 (0x9)\n        Server id: Pymodbus\n        Run indicator: ON (0xff)\n        CRC: ",
    "        Byte count: 5 (0x5)\n        Server id: 0102\n        Run indicator: OFF (0x00)\n"
    "        Additional data: AB\n        CRC: ",
    "        Byte count: 8 (0x8)\n        Server id: 123456789abc\n        Run indicator: ON (0xff)\n"
    "        Additional data: 07\n        CRC: ",
]
PLUGIN_FIELDS = [  # the plugin's FC17 fields (a longer id: vw3.server_id_text or vw3.server_id_bytes)
    {"byte_count": "9", "server_id_text": "Pymodbus", "run_indicator": "0xff"},
    {"byte_count": "5", "server_id_bytes": "01:02", "run_indicator": "0x00", "additional_data": "AB"},
    {"byte_count": "8", "server_id_bytes": "12:34:56:78:9a:bc", "run_indicator": "0xff", "additional_bytes": "07"},
]
FC17_FIELDS = ("byte_count", "server_id", "server_id_text", "server_id_bytes", "run_indicator", "additional_data",
               "additional_bytes")


def test_pymodbus_reads_its_answer_as_we_do() -> None:
    """The peer's own encoder gives the bytes, its decoder the identifier and status we show."""
    from pymodbus.pdu import other_message  # (the test extra: missing, the test fails, never skips)
    response = other_message.ReportDeviceIdResponse(identifier=b"Pymodbus", status=True, dev_id=5)
    assert bytes([5, 17]) + response.encode() == FRAMES[1][:-2]
    decoded = other_message.ReportDeviceIdResponse()
    decoded.decode(FRAMES[1][2:-2])
    assert (decoded.identifier.decode(), "ON" if decoded.status else "OFF") == (
        FIELDS[0]["server_id"], FIELDS[0]["run_indicator"])


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_reads_the_longer_id(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    assert decode_frames(FRAMES, tmp_path, monkeypatch, pure).splitlines()[1::2] == LINES
    answers = [json.loads(line) for line in decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--json")
               .splitlines()][1::2]
    assert [answer["fields"] for answer in answers] == FIELDS
    assert [answer["warnings"] for answer in answers] == WARNINGS[1::2]
    detail = decode_frames(FRAMES, tmp_path, monkeypatch, pure, "-V")
    for tree in TREES:
        assert tree in detail


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_reads_the_longer_id(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
    assert [{key: value for key, value in item.fields.items() if key in FC17_FIELDS}
            for item in items[1::2]] == PLUGIN_FIELDS
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass).stdout.splitlines()
    assert [line.split(" [")[0] for line in info[1::2]] == [
        "5 Report Server ID response " + line.split("Report Server ID ")[1].split(" [")[0] for line in LINES]
