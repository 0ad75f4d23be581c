"""The plugin reads FC17's run indicator as vw3-decode does (tests/unit/test_server_id_length.py): pymodbus's
answer (a name as the server id, the run indicator last) and a two-byte id draw a warning that gives the
length the id is read with; an answer with no 00 or FF after its first byte one that there is no run indicator, in
vw3-decode's words."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

REQUEST = "0C 11 C4 BC"
FRAMES = [
    REQUEST, "0C 11 1F " + b"Telemecanique-ATV71HU15M3-0201".hex(" ") + " FF B9 C7",
    REQUEST, "0C 11 04 01 02 FF 41 04 7D",
    REQUEST, "0C 11 04 01 02 03 41 45 7D",
]


def test_a_longer_server_id_is_no_bad_run_indicator(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(bytes.fromhex(frame), 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap)
    assert [item.texts.get("warning", []) for item in items] == [
        [], ["server id of 30 bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte "
             "id, 0x65 is no run indicator"],
        [], ["server id of 2 bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte "
             "id, 0x02 is no run indicator"],
        [], ["run indicator 0x02 is neither 0x00 (OFF) nor 0xFF (ON)"],
    ]
