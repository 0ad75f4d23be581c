"""A Read Coils or Read Discrete Inputs answer pads its last byte with zeros past the bits asked (Application
Protocol 6.1, 6.2): bits set there draw a warning naming them, as the last byte's mask (data/modbus.toml
[lift.read_bits_response] padding; fields.lifter, the engine's lift_frame hands such an answer to Python, the
plugin's generated lifter). A clean answer, and one of a multiple of 8 bits, draw none. Before, every engine
was silent. vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# 10 coils asked, bit 10 (0x04 of the last byte) set; 10 inputs, bits 10..15 set; 10 clean; 16 all set
FRAMES = [rtu("0C 01 00 00 00 0A"), rtu("0C 01 02 FF 07"), rtu("0C 02 00 00 00 0A"), rtu("0C 02 02 FF FC"),
          rtu("0C 01 00 00 00 0A"), rtu("0C 01 02 FF 03"), rtu("0C 02 00 00 00 10"), rtu("0C 02 02 FF FF")]
WARNINGS = [[], ["padding bits set after the bits asked (10): 0x04"],
            [], ["padding bits set after the bits asked (10): 0xFC"], [], [], [], []]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_warns_of_padding_bits(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure)
    assert out.splitlines()[1::2] == [
        "     2            -  12 response  Read Coils 0..9 (10): 1111111111 [#1] "
        f"[warning: {WARNINGS[1][0]}]  CRC ok",
        "     4            -  12 response  Read Discrete Inputs 0..9 (10): 1111111100 [#3] "
        f"[warning: {WARNINGS[3][0]}]  CRC ok",
        "     6            -  12 response  Read Coils 0..9 (10): 1111111111 [#5]  CRC ok",
        "     8            -  12 response  Read Discrete Inputs 0..15 (16): 1111111111111111 [#7]  CRC ok",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_warns_of_padding_bits(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "bits.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
