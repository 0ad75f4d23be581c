"""The plugin warns of an FC43/14 object longer than its device allows as vw3-decode does
(tests/unit/test_object_length.py): the ATV71 card's UserApplicationName of 17 bytes, not one of 16."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import run_tshark, write_pcap

pytestmark = pytest.mark.integration

REQUEST = "01 2B 0E 02 06 F0 85"
FRAMES = [
    REQUEST, "01 2B 0E 02 02 00 00 01 06 11 " + b"ABCDEFGHIJKLMNOPQ".hex(" ") + " 9A 45",
    REQUEST, "01 2B 0E 02 02 00 00 01 06 10 " + b"ABCDEFGHIJKLMNOP".hex(" ") + " F3 4A",
]


def test_a_device_name_past_16_bytes_is_warned(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc43.pcap", [(bytes.fromhex(frame), 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.warning").stdout.splitlines()
    assert got == ["1|", "2|UserApplicationName of 17 bytes is longer than the VW3 A3 303's 16", "3|", "4|"]
