"""Counts read in one style across the outputs (describe.count_text: `2000 frames`, `1 frame`, no thousands
separator, as tshark writes its counts): --stats' bus timing said `1,000 items stamped earlier than the item
before` and the overlap warning `1,999 frames would overlap the one before` beside the first line's
`2000 frames` and `inter-frame gaps: 1999`. Exact outputs for exact bytes, the engine and the Python stages
(VW3_PURE_PYTHON=1) alike (assert_same)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import assert_same, write_pcap

REQUEST, RESPONSE = rtu("01 03 0C82 0001"), rtu("01 03 02 0064")
T0 = 1_700_000_000 * 10**9
PAIRS = 1000


def test_thousand_backwards_counts_read_as_the_first_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """1000 polls whose answer is stamped 1 ms before its request: 1000 items and 1000 responses back in time."""
    capture = tmp_path / "back.pcap"
    records = []
    for k in range(PAIRS):
        records += [(REQUEST, T0 + k * 10**8), (RESPONSE, T0 + k * 10**8 - 10**6)]
    write_pcap(capture, records)
    out, _ = assert_same([str(capture), "--stats", "-n"], monkeypatch)
    lines = out.splitlines()
    assert lines[0] == "2000 frames, 0 noise bytes in 0 runs"
    assert ("time going backwards, left out of the timing: 1000 items stamped earlier than the item before, "
            "1000 responses earlier than its request") in lines
    assert not [line for line in lines if "1,000" in line]


def test_overlap_warning_counts_as_the_first_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """2000 frames 2 ms apart, each 8 or 7 bytes long: at 9600 baud (9.2 ms a request) each overlaps the one before."""
    capture = tmp_path / "fast.pcap"
    write_pcap(capture, [(REQUEST if k % 2 == 0 else RESPONSE, T0 + k * 2 * 10**6) for k in range(2 * PAIRS)])
    out, _ = assert_same([str(capture), "--stats", "-n", "--baud", "9600"], monkeypatch)
    lines = out.splitlines()
    assert lines[0] == "2000 frames, 0 noise bytes in 0 runs"
    assert ("vw3-decode: warning: --baud 9600: 1999 frames would overlap the one before at 9600 baud: "
            "the line is faster?") in lines
    assert [line for line in lines if line.startswith("inter-frame gaps: ")][0].startswith(
        "inter-frame gaps: 1999, 1999 below t3.5;")


def test_one_backwards_item_reads_singular(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "one.pcap"
    write_pcap(capture, [(REQUEST, T0), (RESPONSE, T0 - 10**6), (REQUEST, T0 + 10**8), (RESPONSE, T0 + 10**8 + 10**7)])
    out, _ = assert_same([str(capture), "--stats", "-n"], monkeypatch)
    assert ("time going backwards, left out of the timing: 1 item stamped earlier than the item before, "
            "1 response earlier than its request") in out.splitlines()


def test_clamped_times_counted_as_the_first_line(tmp_path: Path) -> None:
    """-w to pcap of 1000 records stamped in 2200 (past what pcap's 32-bit seconds hold)."""
    from dissector.render.pcapngwriter import PcapngWriter
    from helpers import run_cli

    capture, written = tmp_path / "late.pcapng", tmp_path / "out.pcap"
    with capture.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False)
        for k in range(PAIRS):
            writer.write(REQUEST if k % 2 == 0 else RESPONSE, 7_258_118_401.0 + k * 0.01)
    status, out, err = run_cli([str(capture), "-w", str(written)])
    assert (status, out) == (0, "")
    assert err == (f"vw3-decode: warning: -w {written}: 1000 records' times outside what pcap holds, "
                   "written at the nearest time it holds\n")


def test_a_full_disk_counts_whole_records_as_the_first_line(tmp_path: Path) -> None:
    """RLIMIT_FSIZE makes the kernel write part of a batch and then fail (EFBIG), as a full disk does:
    the records and bytes kept without a thousands separator (test_hostile checks what is kept)."""
    import os
    import re
    import resource
    import subprocess
    import sys

    from conftest import ROOT

    capture = tmp_path / "big.bin"
    capture.write_bytes((ROOT / "captures" / "atv71_commissioning.bin").read_bytes() * 200)
    written = tmp_path / "out.pcap"
    done = subprocess.run([sys.executable, "-m", "dissector", str(capture), "-w", str(written)],
                          capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(ROOT)},
                          preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (100_001, 100_001)),
                          timeout=120)
    assert done.returncode == 1
    match = re.fullmatch(rf"vw3-decode: -w {written}: File too large; {written} keeps (\d+) whole records "
                         r"\((\d+) bytes\)\n", done.stderr)
    assert match, done.stderr
    assert int(match[1]) > 1000 and int(match[2]) == written.stat().st_size
