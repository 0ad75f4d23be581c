"""--live at a speed with no termios constant (14400, 28800, 76800 baud: pyserial sets them as a custom
speed) on a port the run before left at such a speed (hunt62): the second run was refused,
`cannot open /dev/pts/3: the port refused the settings: Invalid argument`, exit 2, so a capture stopped
with Ctrl-C at 14400 baud could not be started again until the port was opened at a standard speed.
The port keeps its settings between runs as an adapter does (the test holds the pseudo-terminal open)."""
from __future__ import annotations

import array
import fcntl
import os
import subprocess
import sys

import pytest

from live_bus import ROOT, open_pty

pytestmark = pytest.mark.integration
TCGETS2 = 0x802C542A  # (asm-generic: _IOR('T', 0x2A, struct termios2), 44 bytes)


def _speed(fd: int) -> int:
    buf = array.array("i", [0] * 64)
    fcntl.ioctl(fd, TCGETS2, buf)
    return buf[10]  # c_ospeed


@pytest.mark.parametrize("bauds", [(14400, 14400), (76800, 28800), (28800, 19200, 28800)])
def test_a_custom_speed_opens_again(bauds: tuple[int, ...]) -> None:
    master, slave, path = open_pty()
    try:
        for baud in bauds:
            done = subprocess.run([sys.executable, "-m", "dissector", "--live", path, "--baud", str(baud),
                                   "--duration", "0.2"], cwd=ROOT, capture_output=True, text=True, timeout=60)
            assert done.returncode == 0, done.stderr
            assert done.stderr.splitlines()[0] == f"vw3-decode: listening on {path} at {baud} 8E1"
            assert _speed(slave) == baud
    finally:
        os.close(master)
        os.close(slave)
