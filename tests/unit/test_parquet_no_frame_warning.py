"""--parquet DIR on a capture in which no frame checks (another format, a line read at the wrong speed, every
record cut by a snapshot length) says so, as the decode of the same file does (app/inputs.py
no_frame_text), whichever worker read it. Before (hunt67b), --parquet wrote its noise rows and said nothing:
`rnd.bin: 1 frame, 0 registers, 1 event`, where `vw3-decode rnd.bin` warns `no valid Modbus RTU frame in
300 bytes ...: not a Modbus capture, or another format or line speed?`."""
from __future__ import annotations

import random
import struct
from pathlib import Path

import pytest

from helpers import run_cli

REQUEST = bytes.fromhex("0C 03 20 D0 00 03 0E EF")  # VW3 A3 303 p.38's read of 8400..8402 (3)
HEADER = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)


def _captures(tmp_path: Path) -> tuple[str, str, str]:
    good, cut, other = tmp_path / "good.pcap", tmp_path / "cut.pcap", tmp_path / "rnd.bin"
    good.write_bytes(HEADER + struct.pack("<IIII", 1_767_225_600, 0, 8, 8) + REQUEST)
    cut.write_bytes(HEADER + struct.pack("<IIII", 1_767_225_600, 0, 6, 8) + REQUEST[:6])  # snapshot length 6
    other.write_bytes(random.Random(67).randbytes(300))
    return str(good), str(cut), str(other)


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_parquet_says_what_the_decode_says(tmp_path: Path, jobs: str) -> None:
    good, cut, other = _captures(tmp_path)
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), "--jobs", jobs, good, cut, other])
    assert status == 0 and len(out.splitlines()) == 3
    said = sorted(err.splitlines())
    assert said == sorted([
        f"vw3-decode: warning: {cut}: record 1: only 6 of its 8 bytes were captured",
        f"vw3-decode: warning: {cut}: no frame can be checked: every record was captured in part (1 record, 6 bytes: "
        "a snapshot length shorter than the frames), their CRCs cut off: capture again with a larger snapshot length",
        f"vw3-decode: warning: {other}: no valid Modbus RTU frame in 300 bytes (every item is noise or a frame with a "
        "bad check): not a Modbus capture, or another format or line speed?",
    ])
    decoded = run_cli(["-q", "--stats", good, cut, other])[2].splitlines()
    assert sorted(line for line in decoded if "baud" not in line) == said


def test_one_capture_alone(tmp_path: Path) -> None:
    _good, _cut, other = _captures(tmp_path)
    assert run_cli(["--parquet", str(tmp_path / "data"), other])[2] == (
        f"vw3-decode: warning: {other}: no valid Modbus RTU frame in 300 bytes (every item is noise or a frame with "
        "a bad check): not a Modbus capture, or another format or line speed?\n")
