"""--live given what is no serial port (hunt62): a capture file (`--live capture.pcap`, a file where a port
belongs) or a device that is no terminal (/dev/null). Before, pyserial's words came through:
`cannot open p38_protection.pcap: Could not configure port: (25, 'Inappropriate ioctl for device')`."""
from __future__ import annotations

import subprocess
import sys

import pytest

from live_bus import ROOT

pytestmark = pytest.mark.integration


@pytest.mark.parametrize("port, why", [
    ("captures/p38_protection.pcap", "a file, not a serial port (decode a capture file without --live)"),
    ("/dev/null", "not a serial port (it takes no line settings)"),
])
@pytest.mark.parametrize("detect", [[], ["--detect"]])
def test_what_is_no_port_is_said_in_one_line(port: str, why: str, detect: list[str]) -> None:
    done = subprocess.run([sys.executable, "-m", "dissector", "--live", port, *detect], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stdout, done.stderr) == (2, "", f"vw3-decode: cannot open {port}: {why}\n")
