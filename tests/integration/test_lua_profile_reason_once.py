"""The plugin's profile reason is the text vw3-decode shows (tests/unit/test_profile_reason_once.py): it
names the frame that decided it, once. Real tshark with -X lua_script:lua/vw3.lua, -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
# Read Device Identification of slave 1 (its answer: ProductCode ATV71HU15M3), then a read of 8400.
FRAMES = [rtu("01 2B 0E 01 00"), rtu("01 2B 0E 01 01 00 00 01 01 0B " + b"ATV71HU15M3".hex()),
          rtu("01 03 20 D0 00 01"), rtu("01 03 02 00 05")]
REASON = "Read Device Identification in frame #2: ProductCode 'ATV71HU15M3'"


def test_why_this_profile_names_the_frame_once(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "id.pcap", [(frame, T0 + 0.05 * index) for index, frame in enumerate(FRAMES)])
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    lines = [line for line in result.stdout.splitlines() if "profile" in line.lower()]
    assert lines == [
        "    [Device profile: atv71]", f"    [Why this profile: {REASON}]",
        "    [Device profile: atv71]", f"    [Why this profile: {REASON}]",
        f"    [Profile chosen: slave 1: atv71 ({REASON})]",
        "    [Device profile: atv71]", f"    [Why this profile: {REASON}]",
        "    [Device profile: atv71]", f"    [Why this profile: {REASON}]",
    ]
