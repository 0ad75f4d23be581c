"""vw3-decode -V names a PDU field as the plugin's tree names its field (data/fields.toml title and value
strings, as Wireshark writes a value string): a request's `Start address: 8400` (before: `Start:`, while its
answer said `[Start address: 8400]`), FC8's `Sub-function: Return Query Data (0)` (before: `Subfunction: 0
(0x0)`), an exception's `Exception code: Illegal Data Address (2)` (before: `Exception: 2 Illegal Data
Address`), `Unknown (9)` for a code the spec does not name, as Wireshark's value strings. Hex is compared
regardless of case and the plugin's DEC fields without vw3-decode's shortest hex, as
test_lua_tree_window_lines.py does. Real tshark."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = ["0C 03 20D0 0003", "0C 83 02", "01 08 0000 A537", "01 08 0000 A537", "01 08 0063 0000",
          "01 0F 0013 000A 02 CD 01", "01 8F 09"]
WANTED = ("Start address:", "Sub-function:", "Exception code:")
EXPECTED = ["Start address: 8400 (0x20D0)", "Exception code: Illegal Data Address (2)",
            "Sub-function: Return Query Data (0)", "Sub-function: Return Query Data (0)",
            "Sub-function: Unknown (99)", "Start address: 19 (0x13)", "Exception code: Unknown (9)"]


def _lines(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if line.strip().startswith(WANTED)]


def test_names_as_the_plugin(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "names.pcap", [(rtu(frame), 1767225600 + 0.01 * index)
                                                for index, frame in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    assert _lines(python) == EXPECTED
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    # (the plugin's vw3.start is DEC: no hex after it)
    assert _lines(result.stdout) == [re.sub(r"^(Start address: \d+) \(0x\w+\)$", r"\1", line) for line in EXPECTED]


def test_exception_meaning_as_the_plugin() -> None:
    """A device's meaning of an exception: `Exception meaning on this device: ...` (the plugin's field title;
    before: `Meaning on this device: ...`)."""
    capture = ROOT / "captures" / "p38_protection.pcap"
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(capture)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    ours = [line.strip() for line in python.splitlines() if "meaning on this device" in line.lower()]
    result = run_tshark(capture, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    theirs = [line.strip()[1:-1] for line in result.stdout.splitlines()
              if line.strip().startswith("[Exception meaning on this device:")]
    assert len(ours) == 2 and ours[0].startswith("Exception meaning on this device: address does not exist")
    assert ours == theirs
