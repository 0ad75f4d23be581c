"""`-w FILE --frame-records` writes each frame (and noise run) as one record at its time, for Wireshark's
mbrtu, which reads a frame only whole in one record: a tap's capture in reads of 1..16 bytes (hunt 56,
pymodbus 3.16.1 answering mbpoll on a pty) copied by plain `-w` keeps its reads (mbrtu: most frames
unreadable), with --frame-records every frame is a Modbus RTU frame to tshark's mbrtu, and the copy decodes
back to the same items. Without -w the option is refused."""
from __future__ import annotations

import random
import subprocess
import sys
from pathlib import Path

from conftest import ROOT
from helpers import rtu, run_cli
from lua_harness import write_pcap

CHAR_NS = 573_000  # a character at 19200 baud, 11 bits
FRAMES = ["0C 04 000A 0002", "0C 04 04 000A 000B", "01 01 0000 000A", "01 01 02 AA 02", "01 06 2329 000A",
          "01 06 2329 000A", "01 10 00C8 0004 08 0001 0002 0003 FFFF", "01 10 00C8 0004",
          "01 16 0028 00F2 0025", "01 16 0028 00F2 0025", "01 03 4E1F 000A", "01 83 02"]
MBRTU = ["-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""']


def _tap_capture(path: Path) -> None:
    """The frames 60 ms apart (an answer 0.8 ms after its request), each in reads of 1..16 bytes."""
    rng, records, ns = random.Random(56), [], 1_796_533_144 * 1_000_000_000  # (in us: the pcap's)
    for index, text in enumerate(FRAMES):
        frame, at = rtu(text), 0
        while at < len(frame):
            size = rng.randint(1, 16)
            records.append((frame[at : at + size], (ns + at * CHAR_NS) / 1e9))
            at += size
        ns += len(frame) * CHAR_NS + (800_000 if index % 2 == 0 else 60_000_000)
    write_pcap(path, records)


def _mbrtu(path: Path) -> list[str]:
    out = subprocess.run(["tshark", *MBRTU, "-r", str(path)], capture_output=True, text=True, check=True).stdout
    return out.splitlines()


def test_frame_records_are_read_by_mbrtu(tmp_path: Path) -> None:
    tap, reads, frames = tmp_path / "tap.pcap", tmp_path / "reads.pcap", tmp_path / "frames.pcap"
    _tap_capture(tap)
    assert run_cli(["-w", str(reads), str(tap)])[0] == 0
    status, out, err = run_cli(["-w", str(frames), "--frame-records", str(tap)])
    assert (status, out, err) == (0, "", "")
    assert len(_mbrtu(reads)) > len(FRAMES)  # (its reads: a frame over several records)
    lines = _mbrtu(frames)
    assert len(lines) == len(FRAMES) and all(" Modbus RTU " in line for line in lines), lines
    assert "Query: Unit:  12, Func:   4" in lines[0] and "Exception returned" in lines[-1]
    decoded = [run_cli([str(path)]) for path in (tap, frames)]
    assert decoded[0][0] == 0 and decoded[0] == decoded[1]


def test_frame_records_needs_w(tmp_path: Path) -> None:
    _tap_capture(tmp_path / "tap.pcap")
    assert run_cli(["--frame-records", str(tmp_path / "tap.pcap")]) == (
        2, "", "vw3-decode: --frame-records needs -w FILE\n")
