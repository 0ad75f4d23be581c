"""--parquet DIR with several captures: a warning that numbers a record names its file, as the decode's does
(app/inputs.py _named, hunt63), whichever worker read it. Before (hunt67b), `--parquet DIR good.pcap cut.pcap`
said `warning: record 1: the capture ends inside its header (6 of 16 bytes)`, any file's, and with --jobs 2
the summary lines come in the order the workers end. One capture's warnings are as they were."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli

REQUEST = bytes.fromhex("0C 03 20 D0 00 03 0E EF")  # VW3 A3 303 p.38's read of 8400..8402 (3)
HEADER = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
RECORD = struct.pack("<IIII", 1_767_225_600, 0, len(REQUEST), len(REQUEST)) + REQUEST


def _captures(tmp_path: Path) -> tuple[str, str]:
    good, cut = tmp_path / "good.pcap", tmp_path / "cut.pcap"
    good.write_bytes(HEADER + RECORD)
    cut.write_bytes(HEADER + RECORD[:6])  # the capture ends inside the record's header
    return str(good), str(cut)


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_each_file_named_in_its_record_warnings(tmp_path: Path, jobs: str) -> None:
    good, cut = _captures(tmp_path)
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), "--jobs", jobs, good, cut])
    assert status == 0
    assert sorted(out.splitlines()) == [f"{cut}: 0 frames, 0 registers, 0 events",
                                        f"{good}: 1 frame, 0 registers, 0 events"]
    assert err == f"vw3-decode: warning: {cut}: record 1: the capture ends inside its header (6 of 16 bytes)\n"
    # as the decode of the same files says it
    assert run_cli(["-q", "--stats", good, cut])[2].splitlines()[0] == err.rstrip("\n")


def test_one_capture_as_before(tmp_path: Path) -> None:
    _good, cut = _captures(tmp_path)
    assert run_cli(["--parquet", str(tmp_path / "data"), cut])[2] == (
        "vw3-decode: warning: record 1: the capture ends inside its header (6 of 16 bytes)\n")
