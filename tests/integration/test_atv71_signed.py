"""ATV71 parameters the drive sends as signed 16-bit words (data/maps/atv71.csv, column `signed`, source B:
B&R's ACOPOSinverter P74 parameter table, 's'): the frequencies and speeds (RFR, FRH, LFR, LFRD, RFRD,
FRHD), negative in reverse, and torque and power (OTR, OPR), negative when braking. Before, only RFR was
marked: 16#FFF6 in FRH read 6552.6 Hz, in OTR 65526 %, in LFRD 65436 rpm. Every engine reads the same map
data (devices/maps.py, lua/src/maps.lua; the compiled engine formats values from the Python map rows):
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("0C 03 0C82 0004"), rtu("0C 03 08 FFF6 FFF6 0010 FFFB"),  # RFR, FRH, LCR (unsigned), OTR
          rtu("0C 06 2136 FFF6"), rtu("0C 06 2136 FFF6"),  # LFR = 16#FFF6 and its echo
          rtu("0C 03 219A 0004"), rtu("0C 03 08 FF9C 0000 FF9C FF9C"),  # LFRD, ETAD, RFRD, FRHD
          rtu("0C 03 0C8B 0001"), rtu("0C 03 02 FFCE")]  # OPR
LINES = [
    "     2            -  12 response  Read Holding Registers 3202..3205 (4): RFR=-1.0 Hz FRH=-1.0 Hz LCR=1.6 A "
    "OTR=-5 % [#1]  CRC ok",
    "     3            -  12 request   Write Single Register 8502 LFR=-1.0 Hz  CRC ok",
    "     6            -  12 response  Read Holding Registers 8602..8605 (4): LFRD=-100 rpm ETAD=no bit set "
    "RFRD=-100 rpm FRHD=-100 rpm [#5]  CRC ok",
    "     8            -  12 response  Read Holding Registers 3211: OPR=-50 % [#7]  CRC ok",
]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_reads_signed_parameters(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    lines = decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--profile", "atv71").splitlines()
    assert [lines[1], lines[2], lines[5], lines[7]] == LINES


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_reads_signed_parameters(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "signed.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71", two_pass=two_pass)
    assert [[(reg.get("code"), reg.get("text")) for reg in item.registers] for item in items[1::2]] == [
        [("RFR", "-1.0 Hz"), ("FRH", "-1.0 Hz"), ("LCR", "1.6 A"), ("OTR", "-5 %")], [("LFR", "-1.0 Hz")],
        [("LFRD", "-100 rpm"), ("ETAD", "no bit set"), ("RFRD", "-100 rpm"), ("FRHD", "-100 rpm")],
        [("OPR", "-50 %")]]
