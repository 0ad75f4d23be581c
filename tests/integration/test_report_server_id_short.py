"""Report Server ID (FC17) answers shorter than the spec's id and run indicator status (Application Protocol
6.17 puts both first), in each engine: vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin
(tshark -2 and one pass).
- Byte count 1 holds the server id alone: the id is shown (`server id 180`) and the missing run indicator
  warned (the layout's run_indicator and additional_data are `?(byte_count-1)`: data/modbus.toml,
  protocol/shapes.py, protocol/layouts.py, codegen/decode_lua.py). Before, all three said `Report Server ID
  (malformed)`. Wireshark 4.0 shows FC17's data as bytes only (Modbus/TCP: `Data: 01b4`; mbrtu does not
  classify it): no oracle either way.
- Byte count 0 holds neither, said in words (the layout's server_id is `?(byte_count)`;
  fields._report_server_id_response and lua/src/decode.lua write the text no_server_id). Before, vw3-decode
  said `Report Server ID (malformed) [warning: malformed response: stream read less than specified amount,
  expected 1, found 0 at (parsing) -> server_id]` (the parser's words) and the plugin `malformed response:
  too short for byte_count and server_id`."""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration


@dataclass(frozen=True)
class Case:
    frames: list[bytes]
    warning: str
    line: str  # vw3-decode's summary line of the answer
    fields: dict  # its --json fields
    tree: str  # its -V lines, from the byte count to the CRC
    plugin_fields: dict  # the plugin's fields of the answer that are there
    info: str  # the plugin's Info column, before any [bracket]


ALONE_WARNING = "no run indicator status: byte count 1 holds the server id alone"
EMPTY_WARNING = "no server id and no run indicator status: byte count 0 holds neither"
CASES = {
    "server id alone": Case(
        [rtu("0C 11"), rtu("0C 11 01 B4")], ALONE_WARNING,
        f"     2            -  12 response  Report Server ID server id 180 [#1] [warning: {ALONE_WARNING}]  CRC ok",
        {"byte_count": 1, "server_id": 180},
        "        Byte count: 1 (0x1)\n        Server id: 180 (0xB4)\n        CRC: ",
        {"byte_count": "1", "server_id": "180"}, "12 Report Server ID response server id 180"),
    "empty": Case(
        [rtu("05 11"), rtu("05 11 00")], EMPTY_WARNING,
        f"     2            -   5 response  Report Server ID [#1] [warning: {EMPTY_WARNING}]  CRC ok",
        {"byte_count": 0},
        "        Byte count: 0 (0x0)\n        CRC: ",
        {"byte_count": "0"}, "5 Report Server ID response"),
}
# What neither short answer holds.
ABSENT = ("run_indicator", "additional_data")


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_vw3_decode(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, case: Case) -> None:
    assert decode_frames(case.frames, tmp_path, monkeypatch, pure).splitlines()[1] == case.line
    answer = json.loads(decode_frames(case.frames, tmp_path, monkeypatch, pure, "--json").splitlines()[1])
    assert (answer["fields"], answer["warnings"]) == (case.fields, [case.warning])
    assert case.tree in decode_frames(case.frames, tmp_path, monkeypatch, pure, "-V")


@pytest.mark.parametrize("two_pass", [True, False])
@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_the_plugin(tmp_path: Path, two_pass: bool, case: Case) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(case.frames[0], 1.0), (case.frames[1], 1.01)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    answer = items[1].fields
    assert {key: answer.get(key) for key in ("byte_count", "server_id")} == {
        "byte_count": case.plugin_fields["byte_count"], "server_id": case.plugin_fields.get("server_id")}
    assert not any(key in answer for key in ABSENT)
    assert items[1].texts.get("warning") == [case.warning]
    assert [abbrev for abbrev, _ in items[1].experts] == ["vw3.expert.warning"]
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass).stdout.splitlines()
    assert info[1].split(" [")[0] == case.info  # (one pass: [provisional])
