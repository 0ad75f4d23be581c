"""A Report Server ID (FC17) answer with byte count 0 holds neither the server id nor the run indicator
status (Application Protocol 6.17 puts both first). Each engine shows the byte count and says so in words
(the layout's server_id is `?(byte_count)`: data/modbus.toml; fields._report_server_id_response and
lua/src/decode.lua write the text no_server_id). Before, vw3-decode said `Report Server ID (malformed)
[warning: malformed response: stream read less than specified amount, expected 1, found 0 at (parsing) ->
server_id]` (the parser's words) and the plugin `malformed response: too short for byte_count and server_id`.
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("05 11"), rtu("05 11 00")]
WARNING = "no server id and no run indicator status: byte count 0 holds neither"
LINE = f"     2            -   5 response  Report Server ID [#1] [warning: {WARNING}]  CRC ok"


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_says_the_answer_is_empty(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    assert decode_frames(FRAMES, tmp_path, monkeypatch, pure).splitlines()[1] == LINE
    answer = json.loads(decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--json").splitlines()[1])
    assert (answer["fields"], answer["warnings"]) == ({"byte_count": 0}, [WARNING])
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure, "-V")
    assert "        Byte count: 0 (0x0)\n        CRC: " in out


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_says_the_answer_is_empty(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(FRAMES[0], 1.0), (FRAMES[1], 1.01)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    answer = items[1].fields
    assert answer["byte_count"] == "0" and "server_id" not in answer and "run_indicator" not in answer
    assert items[1].texts.get("warning") == [WARNING]
    assert [abbrev for abbrev, _ in items[1].experts] == ["vw3.expert.warning"]
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass).stdout.splitlines()
    assert info[1].split(" [")[0] == "5 Report Server ID response"  # (one pass: [provisional])
