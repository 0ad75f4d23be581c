"""vw3-decode -V and the plugin's tree say FC17's run indicator and FC12's empty event log alike (hunt 56 D4,
pymodbus 3.16's answers): the run indicator named as Wireshark names a value of a HEX field, `ON (0xff)`,
`Unknown (0x76)` (before: vw3-decode `118 (0x76)`, `ON`); no Events line for a log of no events, as the plugin
and Wireshark's own modbus dissector show none (before: vw3-decode `Events: (empty)`). Real tshark."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
T0 = 1767225600.0
FRAMES = [rtu("01 0C"), rtu("01 0C 06 00 00 00 00 00 00"),  # FC12: status 0, 0 events, 0 messages, no events
          rtu("01 11"), rtu("01 11 04 45 76 41 42"),  # FC17: server id 69, run indicator 0x76, 'AB'
          rtu("01 11"), rtu("01 11 04 45 FF 41 42")]  # run ON
WANTED = ("Events", "Run indicator")
EXPECTED = ["Run indicator: Unknown (0x76)", "Run indicator: ON (0xff)"]


def _lines(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if line.strip().startswith(WANTED)]


def test_vw3_decode_and_the_plugin_say_the_same(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "d4.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    assert _lines(python) == EXPECTED
    assert "        Run indicator: Unknown (0x76)\n        Additional data: AB\n" in python
    assert "Message count: 0 (0x0)\n        CRC: " in python  # (no Events line between them)
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert _lines(result.stdout) == EXPECTED
