"""An FC20 sub-response's length byte counts bytes (the reference type and 2 per register), its sub-request's
record length registers (Application Protocol 6.14): the warning says what the length holds in registers,
beside the registers asked (protocol/rules.py PartLength.held). Before, 'sub-response 1's length 5 disagrees
with the record length asked (1)' set bytes against registers. vw3-decode (compiled engine, VW3_PURE_PYTHON=1)
and the plugin."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# one register asked of each of two records, two sent; then 2 asked, a length of 4 (1 register and a byte)
FRAMES = [rtu("05 14 0E 06 0004 0001 0001 06 0003 0009 0001"), rtu("05 14 0C 05 06 0DFE 0020 05 06 33CD 0040"),
          rtu("05 14 07 06 0004 0001 0002"), rtu("05 14 05 04 06 0DFE 00")]
WARNINGS = [[], ["sub-response 1's length 5 holds registers (2), not the record length asked (1)",
                 "sub-response 2's length 5 holds registers (2), not the record length asked (1)"],
            [], ["sub-response 1's length 4 holds registers (1 and 1 byte(s)), not the record length asked (2)"]]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_says_the_length_in_registers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure)
    lines = out.splitlines()
    assert lines[1] == ("     2            -   5 response  Read File Record 2 record group(s) [#1] "
                        + " ".join(f"[warning: {w}]" for w in WARNINGS[1]) + "  CRC ok")
    assert lines[3].endswith(f"[#3] [warning: {WARNINGS[3][0]}]  CRC ok")


def test_the_plugin_says_the_length_in_registers(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc20.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
