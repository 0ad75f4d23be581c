"""A Report Server ID (FC17) answer whose byte after a one-byte server id is no run indicator (00 OFF, FF ON)
while a later byte is: pymodbus answers `09 'Pymodbus' FF`, its server id a name, the run indicator last
(the spec's server id is device specific in length, Application Protocol 6.17). The one-byte reading
(libmodbus's: `server id 80, run 121, 7 bytes`) stays, with a warning that 0x79 is no run indicator and
the id probably runs to the first 00 or FF after its first byte (as text where printable, else its bytes):
fields.py _report_server_id_response, lua/src/decode.lua. Before, every engine was silent. Wireshark 4.0
shows FC17's data as bytes only over Modbus/TCP (`Data: 0950796d6f64627573ff`): no oracle.
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("05 11"), rtu("05 11 09 50 79 6D 6F 64 62 75 73 FF"),  # pymodbus: 'Pymodbus', then ON
          rtu("05 11"), rtu("05 11 05 01 02 00 41 42")]  # a two-byte id 01 02, then OFF, 00 41 42
NOT_RUN = "run indicator 0x{:02X} is neither 0x00 (OFF) nor 0xFF (ON): the server id is probably "
WARNINGS = [[], [NOT_RUN.format(0x79) + "'Pymodbus', then run ON"],
            [], [NOT_RUN.format(0x02) + "01 02, then run OFF"]]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_says_the_longer_id(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure)
    assert out.splitlines()[1::2] == [
        f"     2            -   5 response  Report Server ID server id 80, run 121, 7 bytes [#1] "
        f"[warning: {WARNINGS[1][0]}]  CRC ok",
        f"     4            -   5 response  Report Server ID server id 1, run 2, 3 bytes [#3] "
        f"[warning: {WARNINGS[3][0]}]  CRC ok",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_says_the_longer_id(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
