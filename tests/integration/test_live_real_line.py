"""Issue 26 live: the real RS-485 line of tests/corpus (a glitch byte after every frame) written at line
rate into `vw3-decode --live` on a pseudo-terminal: every frame found as the node's RX/TX channels carry
them, no slave that is not on the bus, and the same lines as the decode of the -w file."""
from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from live_bus import ROOT, Bus, paced_writer

pytestmark = pytest.mark.integration
CORPUS = ROOT / "tests" / "corpus"
BAUD = 9600  # the wizmodbus line's


def _records(name: str) -> list[bytes]:
    return [bytes.fromhex(line.partition(" ")[2]) for line in (CORPUS / name).read_text().splitlines()]


def test_the_wizmodbus_line_live_at_9600_baud(tmp_path: Path) -> None:
    stream = b"".join(_records("wizmodbus_bus.records")[:44])  # the first round: 0.49 s of line
    sides = [data.hex() for data in _records("wizmodbus_rxtx.records")]
    bus = Bus(slave=False)
    pcap = tmp_path / "tap.pcap"
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", bus.c_path, "-n", "--baud", str(BAUD), "--json",
         "-w", str(pcap)],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    try:
        # the port is open once it says so (a fixed wait lost the whole line on a loaded machine)
        assert process.stderr.readline().startswith(b"vw3-decode: listening on ")
        assert paced_writer(bus.c, stream, BAUD, piece=8) == 0
        time.sleep(1.0)  # the last frame is closed by the silence
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    finally:
        bus.close()
    assert process.returncode == 0, err.decode()
    live = [json.loads(line) for line in out.decode().splitlines()]
    frames = [item["raw"] for item in live if item["kind"] != "noise"]
    assert frames == sides[:44]
    assert all(item["crc_ok"] for item in live if item["kind"] != "noise")
    assert {item["slave"] for item in live if item["kind"] != "noise"} == {1}
    assert {item["raw"] for item in live if item["kind"] == "noise"} <= {"00", "fe"}
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", "--json", str(pcap)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert [json.loads(line)["raw"] for line in done.stdout.splitlines()] == [item["raw"] for item in live]
