"""A silence of t3.5 or more ends a noise run (framing/stream.py _add_noise, _flush_noise): bytes after it cannot
be the same frame's. A pcap of noise records a second apart was one noise item timed at its first record
('30 bytes of noise', --stats 'load: 100.0 %' for a line busy 0.2 % of the time); now each stretch between
silences is its own item with its own time. Records closer than t3.5 stay one run; the framer's decisions
(frames found) are the same. Exact lines, engine and VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x, --stats)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import assert_same, write_pcap

NOISE = bytes.fromhex("ff00aa")
REQUEST = rtu("0C 03 20D0 0003")
T0 = 1_700_000_000 * 10**9
NOISE_LINE = "- noise     3 bytes of noise at offset {}: ff 00 aa"


def _run(tmp_path: Path, records: list[tuple[bytes, int]], monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str]]:
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, [(data, T0 + ns) for data, ns in records])
    out, _ = assert_same([str(capture)], monkeypatch)
    for option in (["-V"], ["--json"], ["-x"]):
        assert_same([str(capture), *option], monkeypatch)
    stats, _ = assert_same([str(capture), "--stats"], monkeypatch)
    lines = stats.splitlines()
    return out.splitlines(), lines[lines.index("Bus timing") + 2 :]


def test_noise_records_a_second_apart(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out, bus = _run(tmp_path, [(NOISE, 0), (NOISE, 10**9), (NOISE, 2 * 10**9)], monkeypatch)
    assert out == [
        f"     1  0.000000000   {NOISE_LINE.format(0)}",
        f"     2  1.000000000   {NOISE_LINE.format(3)}",
        f"     3  2.000000000   {NOISE_LINE.format(6)}",
        f"vw3-decode: warning: {tmp_path / 'bus.pcap'}: no valid Modbus RTU frame in 9 bytes (every item is noise"
        " or a frame with a bad check): not a Modbus capture, or another format or line speed?",
    ]
    assert bus == [
        "load: 0.3 %",
        "inter-frame gaps: 2, 0 below t3.5; min 998.281 median 998.281 p95 998.281 max 998.281 ms",
        "  500-1000 ms: 2",
        "outages: none",
        out[-1],  # (the warning, as above)
    ]


def test_noise_without_a_silence_stays_one_run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # 2 ms apart at 19200 baud: 0.28 ms of silence after 3 characters, below t3.5 (2.005 ms).
    records = [(NOISE, 0), (NOISE, 2 * 10**6), (NOISE + REQUEST, 3 * 10**9), (NOISE, 4 * 10**9)]
    out, bus = _run(tmp_path, records, monkeypatch)
    assert out == [
        "     1  0.000000000   - noise     6 bytes of noise at offset 0: ff 00 aa ff 00 aa",
        f"     2  3.000000000   {NOISE_LINE.format(6)}",
        "     3  3.000000000  12 request   Read Holding Registers 8400..8402 (3) [the capture ends 1000.0 ms after the"
        " request, within the 1000 ms timeout: not known whether it was answered]  CRC ok",
        f"     4  4.000000000   {NOISE_LINE.format(17)}",
    ]
    assert bus[0] == "load: 0.3 %"
