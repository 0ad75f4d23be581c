"""-Y selects the frames tshark 4.0 selects, checked against a real tshark running the plugin (two
passes) on the shipped captures: a bare field tests presence, raw is bytes as tshark's `frame`, ===
and !==, exponents, escapes, octal, a masked comparison (session 54's hunt, defects 5, 6a, 10, and
their neighbours; tests/unit/test_filter_wireshark.py holds the same frames as numbers)."""
from __future__ import annotations

import pytest

from lua_harness import ROOT, assert_same_frames

CASES = [
    # (capture, vw3-decode -Y, tshark -Y with the plugin)
    ("noisy_bus.pcap", "crc_ok", "vw3.crc_ok"),
    ("noisy_bus.pcap", "!crc_ok", "!vw3.crc_ok"),
    ("noisy_bus.pcap", "crc_ok == 0", "vw3.crc_ok == 0"),
    ("noisy_bus.pcap", "unanswered", "vw3.unanswered"),
    ("noisy_bus.pcap", "!unanswered", "!vw3.unanswered"),
    ("noisy_bus.pcap", "unanswered == 0", "vw3.unanswered == 0"),
    ("noisy_bus.pcap", "broadcast", "vw3.broadcast"),
    ("noisy_bus.pcap", "crc_ok && slave == 12", "vw3.crc_ok && vw3.slave == 12"),
    ("noisy_bus.pcap", "raw contains 0c:03", "frame contains 0c:03"),
    ("noisy_bus.pcap", "raw contains 0C-03", "frame contains 0C-03"),
    ("noisy_bus.pcap", 'raw contains "\\x0c\\x03"', 'frame contains "\\x0c\\x03"'),
    ("noisy_bus.pcap", 'raw contains "0c03"', 'frame contains "0c03"'),
    ("noisy_bus.pcap", "raw[0:2] == 0c:03", "frame[0:2] == 0c:03"),
    ("noisy_bus.pcap", "raw[1:2] == 03:00", "frame[1:2] == 03:00"),
    ("noisy_bus.pcap", "raw[0:2] >= 0c:03", "frame[0:2] >= 0c:03"),
    ("noisy_bus.pcap", "raw[0:2] > 0c", "frame[0:2] > 0c"),
    ("noisy_bus.pcap", "raw[0:2] & 0f", "frame[0:2] & 0f"),
    ("noisy_bus.pcap", 'raw matches "^\\x0c\\x03"', 'frame matches "^\\x0c\\x03"'),
    ("noisy_bus.pcap", "response_time >= 0.0085", "vw3.response_time >= 0.0085"),
    ("noisy_bus.pcap", 'function_name contains "Read\\x20Holding"',
     'vw3.function_name contains "Read\\x20Holding"'),
    ("noisy_bus.pcap", "frame !== 1", "vw3.item !== 1"),
    ("ascii_session.pcap", 'raw contains ":0C03"', 'frame contains ":0C03"'),
    ("atv71_commissioning.pcap", "value === 2", "vw3.reg.value === 2"),
    ("atv71_commissioning.pcap", 'code === "CHCF"', 'vw3.reg.code === "CHCF"'),
    ("p38_protection.pcap", "value !== 3", "vw3.reg.value !== 3"),
    ("p38_protection.pcap", "slave == 014", "vw3.slave == 014"),
    ("p38_protection.pcap", "value & 0x8000 == 0x8000", "vw3.reg.value & 0x8000 == 0x8000"),
    ("p38_protection.pcap", 'code[0:2] == "CH"', 'vw3.reg.code[0:2] == "CH"'),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_the_filter_selects_the_frames_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    path = ROOT / "captures" / capture
    assert_same_frames(path, ours, wiresharks)
