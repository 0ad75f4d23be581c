"""A Report Server ID (FC17) answer with byte count 1 holds the server id alone: the spec's id comes first
(Application Protocol 6.17), its run indicator status after it is missing. Each engine shows the id
(`server id 180`) and warns that the run indicator is missing (the layout's run_indicator and
additional_data are `?(byte_count-1)`: data/modbus.toml, protocol/shapes.py, protocol/layouts.py,
codegen/decode_lua.py). Before, all three said `Report Server ID (malformed)`. Wireshark 4.0 shows FC17's
data as bytes only (Modbus/TCP: `Data: 01b4`; mbrtu does not classify it): no oracle either way.
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("0C 11"), rtu("0C 11 01 B4")]
WARNING = "no run indicator status: byte count 1 holds the server id alone"
LINE = f"     2            -  12 response  Report Server ID server id 180 [#1] [warning: {WARNING}]  CRC ok"


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_shows_the_server_id(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    assert decode_frames(FRAMES, tmp_path, monkeypatch, pure).splitlines()[1] == LINE
    answer = json.loads(decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--json").splitlines()[1])
    assert (answer["fields"], answer["warnings"]) == ({"byte_count": 1, "server_id": 180}, [WARNING])
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure, "-V")
    assert "        Byte count: 1 (0x1)\n        Server id: 180 (0xB4)\n        CRC: " in out


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_shows_the_server_id(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(FRAMES[0], 1.0), (FRAMES[1], 1.01)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    answer = items[1].fields
    assert (answer["byte_count"], answer["server_id"]) == ("1", "180")
    assert "run_indicator" not in answer and "additional_data" not in answer
    assert items[1].texts.get("warning") == [WARNING]
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass).stdout.splitlines()
    assert info[1].split(" [")[0] == "12 Report Server ID response server id 180"  # (one pass: [provisional])
