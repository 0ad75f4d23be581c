"""vw3-decode -V writes a field's bytes and hex as the plugin's tree (Wireshark) writes them: a field of
bytes as one run of hex digits, `Data: a537`, `Status: cd6b05`, `Events: 2000`, `Additional data: 0102`
(before: `a5 37`, ...); FC17's 8-bit server id `Server id: 1 (0x01)` (before `(0x1)`); each word of FC24's
FIFO values and of FC20's and FC21's records at four digits, `[0]: 3582 (0x0DFE)` as the plugin's
`FIFO value`/`Value: 3582 (0x0dfe)` (before `(0xDFE)`). Hex compared regardless of case (vw3-decode writes
upper case, the plugin Wireshark's lower case: test_lua_tree_window_lines.py). Real tshark."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = ["01 08 0000 A537", "01 08 0000 A537", "01 11", "01 11 04 01 12 01 02", "01 0C",
          "01 0C 08 0000 0108 0121 2000", "01 01 0013 0013", "01 01 03 CD 6B 05",
          "01 14 07 06 0004 0001 0002", "01 14 06 05 06 0DFE 0020", "01 18 04DE", "01 18 0006 0002 0001 00A2"]
BYTES = ["Data: a537", "Data: a537", "Additional data: 0102", "Events: 2000", "Status: cd6b05"]
PYTHON_WORDS = ["Server id: 1 (0x01)", "[0]: 3582 (0x0DFE)", "[1]: 32 (0x0020)", "[0]: 1 (0x0001)",
                "[1]: 162 (0x00A2)"]
PLUGIN_WORDS = ["Server id: 1 (0x01)", "Value: 3582 (0x0dfe)", "Value: 32 (0x0020)", "FIFO value: 1 (0x0001)",
                "FIFO value: 162 (0x00a2)"]
_BYTES = re.compile(r"^(Data|Additional data|Events|Status): [0-9a-f]+$")
_WORDS = re.compile(r"^(Server id|\[\d\]|Value|FIFO value): \d+ \(0x")


def _lines(text: str, pattern: re.Pattern[str]) -> list[str]:
    return [line.strip() for line in text.splitlines() if pattern.match(line.strip())]


def test_bytes_and_hex_as_the_plugin(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "hex.pcap", [(rtu(frame), 1767225600 + 0.01 * index)
                                              for index, frame in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert _lines(python, _BYTES) == BYTES
    assert _lines(result.stdout, _BYTES) == BYTES
    assert _lines(python, _WORDS) == PYTHON_WORDS
    assert _lines(result.stdout, _WORDS) == PLUGIN_WORDS
