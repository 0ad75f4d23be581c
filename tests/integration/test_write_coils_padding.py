"""A Write Multiple Coils request pads its outputs value's last byte with zeros past the coils written, as
a Read Coils answer does (Application Protocol 6.11; 6.1, 6.2): bits set there draw the same padding check
of the protocol table, its text naming the coils written (data/modbus.toml [lift.write_coils_request]
padding). Before, an FC1/FC2 answer warned and an FC15 request with the same bits was silent, in every
engine. vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# 10 coils written, bits 10..15 of the last byte set; the answer; 10 written clean; 16 written, all set
FRAMES = [rtu("01 0F 00 13 00 0A 02 CD FF"), rtu("01 0F 00 13 00 0A"), rtu("01 0F 00 13 00 0A 02 CD 03"),
          rtu("01 0F 00 13 00 0A"), rtu("01 0F 00 00 00 10 02 FF FF"), rtu("01 0F 00 00 00 10")]
WARNING = "padding bits set after the coils written (10): 0xFC"
WARNINGS = [[WARNING], [], [], [], [], []]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_warns_of_padding_bits_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   pure: bool) -> None:
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure)
    assert out.splitlines()[0::2] == [
        f"     1            -   1 request   Write Multiple Coils 19..28 (10): 1011001111 [warning: {WARNING}]  CRC ok",
        "     3            -   1 request   Write Multiple Coils 19..28 (10): 1011001111  CRC ok",
        "     5            -   1 request   Write Multiple Coils 0..15 (16): 1111111111111111  CRC ok",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_warns_of_padding_bits_written(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "coils.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
