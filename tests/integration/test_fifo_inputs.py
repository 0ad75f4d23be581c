"""A capture read from a FIFO (`mkfifo bus; tshark -w bus & vw3-decode bus -w copy.pcap`) is read once,
by the decode: nothing before it opens the FIFO to look (its bytes would be gone), nothing after it opens it
again (that waits for a writer that has gone: the decode never ended).

Before, `-w` read the FIFO's head for the pcapng interface to keep (inputs.write_interface) and its time
units (inputs.write_units); profiles (no -n) its magic for a pcapng's buses (inputs.is_pcapng_file); the
line speed its first interface (sources/pcapng.first_interface); and a FIFO of no valid frame was opened
again after the decode for the --mode ascii hint (inputs.holds_ascii): each hung until killed. Now each asks
sources.common.rereadable first, as profile auto does.
"""
from __future__ import annotations

import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from dissector.model import Stamp
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter
from live_bus import ROOT

pytestmark = pytest.mark.integration
REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("010304000100022A32")
T0 = 1_767_225_600_000_000  # us
LINES = [
    "     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok",
    "     3     1.000000   1 request   Read Holding Registers 0..1 (2) [no response]  CRC ok",
]


def capture(path: Path) -> bytes:
    with path.open("wb") as stream:
        pcapng = path.suffix == ".pcapng"
        writer = PcapngWriter(stream, flush=False) if pcapng else PcapWriter(stream, flush=False)
        for data, micros in [(REQUEST, 0), (ANSWER, 10_000), (REQUEST, 1_000_000), (b"", 2_500_000)]:
            writer.write(data, Stamp((T0 + micros) * 1000))
    return path.read_bytes()


def through_fifo(tmp_path: Path, data: bytes, *options: str) -> subprocess.CompletedProcess[str]:
    """vw3-decode reading `data` from a FIFO a thread writes; a decode that hangs fails at the timeout."""
    fifo = tmp_path / "bus"
    os.mkfifo(fifo)

    def feed() -> None:
        with fifo.open("wb") as stream:  # (waits for the decode to open it)
            stream.write(data)

    threading.Thread(target=feed, daemon=True).start()
    return subprocess.run([sys.executable, "-m", "dissector", *options, str(fifo)], cwd=ROOT,
                          capture_output=True, text=True, timeout=30)


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_a_fifo_copied(tmp_path: Path, suffix: str) -> None:
    data = capture(tmp_path / f"live.{suffix}")
    copy = tmp_path / f"copy.{suffix}"
    done = through_fifo(tmp_path, data, "-n", "-w", str(copy))
    assert (done.returncode, done.stdout, done.stderr) == (0, "", "")
    again = subprocess.run([sys.executable, "-m", "dissector", "-n", str(copy)], cwd=ROOT,
                           capture_output=True, text=True, timeout=30)
    assert again.stdout.splitlines() == LINES


def test_a_fifo_with_profiles(tmp_path: Path) -> None:
    done = through_fifo(tmp_path, capture(tmp_path / "live.pcapng"))
    assert done.returncode == 0, done.stderr
    # (profile auto cannot read a FIFO twice: what it chose is provisional, as for standard input)
    assert done.stdout.splitlines()[2] == LINES[2].replace("[no response]", "[no response] [provisional]")


def test_a_fifo_of_no_frame(tmp_path: Path) -> None:
    done = through_fifo(tmp_path, bytes(range(1, 201)), "-n", "-q")
    assert (done.returncode, done.stdout) == (0, "")
    assert done.stderr.endswith(
        "no valid Modbus RTU frame in 200 bytes (every item is noise or a frame with a bad check): not a "
        "Modbus capture, or another format or line speed?\n")
