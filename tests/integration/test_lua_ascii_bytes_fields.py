"""An ASCII frame's fields of bytes (FC8's data, FC12's events, FC15's coil status, FC43's other MEI data) hold
the bytes its hex pairs stand for, as vw3-decode -V shows them (`Data: 012c`): the plugin added them on the
pairs' characters, `Data: 30313243` (the field of bytes reads its range: TreeItem:add takes no value for it).
Now on a data source of their own, `VW3 ASCII data`. Real tshark with -X lua_script:lua/vw3.lua."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
T0 = 1700000000.0
# (PDU hex with its slave, without the LRC; the bytes fields vw3-decode -V shows: (label, hex))
FRAMES = [
    ("0108000B012C", [("Data", "012c")]),
    ("010C080000010801212000", [("Events", "2000")]),
    ("010F0000000A02FF03", [("Status", "ff03")]),
    ("012B0D0A0B", [("Data", "0a0b")]),
]


def ascii_frame(hex_text: str) -> bytes:
    data = bytes.fromhex(hex_text)
    return b":" + (data + bytes([-sum(data) & 0xFF])).hex().upper().encode() + b"\r\n"


def test_the_plugin_holds_the_bytes_vw3_decode_shows(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "ascii.pcap", [(ascii_frame(hex_text), T0 + 0.01 * index)
                                                for index, (hex_text, _) in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], capture_output=True, text=True,
                            check=True).stdout.split("\n\n")
    for frame, (_, shown) in zip(python, FRAMES):
        for label, value in shown:
            assert f"{label}: {value}\n" in frame + "\n"
    got = run_tshark(pcap, "-T", "fields", "-E", "separator=|", "-e", "vw3.data", "-e", "vw3.events", "-e",
                     "vw3.bit_status")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == ["012c||", "|2000|", "||ff03", "0a0b||"]
    tree = run_tshark(pcap, "-V", "-O", "vw3").stdout
    assert [line.strip() for line in tree.splitlines() if line.strip().startswith(("Data:", "Events:", "Status: ff"))] \
        == ["Data: 012c", "Events: 2000", "Status: ff03", "Data: 0a0b"]
