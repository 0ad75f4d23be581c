"""--json's "time" with the capture's digits: a double cannot hold nanoseconds near 1.7e9 s (it kept
1767225600.0090182 of a nanosecond pcap's .009018123), so where microseconds cannot hold the capture's
times (a nanosecond pcap, if_tsresol 10^-7 or 2^-10, as -V's Arrival time: render/timefmt.py
detail_digits) the number is written from the stamp's integer nanoseconds, 9 decimals, as tshark's
frame.time_epoch. Still a JSON number; a microsecond capture's as before. --watch --json's too."""
from __future__ import annotations

import json
import re
import struct
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from test_time_precision import BOTH, NANOS, START, pcap, pcapng


def times(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> list[str]:
    """The "time" number of each line of `vw3-decode argv`, as written; every line is JSON."""
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert all(isinstance(json.loads(line)["time"], float) for line in lines)  # a number, not a string
    return [re.search(r'"time": ([^,]+),', line).group(1) for line in lines]


@BOTH
def test_nanosecond_pcap_json_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcap(tmp_path / "ns.pcap", 10**9, NANOS))
    assert times(["--json", path], monkeypatch, pure) == ["1767225600.009018123", "1767225600.022017123"]
    # through -Y's records, and -T json
    assert times(["-T", "json", "-Y", 'kind == "response"', path], monkeypatch, pure) == ["1767225600.022017123"]


@BOTH
def test_binary_resolution_json_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcapng(tmp_path / "b10.pcapng", 0x80 | 10, [START * 1024 + 146, START * 1024 + 167]))
    assert times(["--json", path], monkeypatch, pure) == ["1767225600.142578125", "1767225600.163085937"]


@BOTH
def test_microsecond_capture_unchanged(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcap(tmp_path / "us.pcap", 10**6, [START * 10**6 + 500_000, START * 10**6 + 522_017]))
    assert times(["--json", path], monkeypatch, pure) == ["1767225600.5", "1767225600.522017"]  # json's float
    ms = str(pcapng(tmp_path / "ms.pcapng", 3, [START * 1000 + 146, START * 1000 + 167]))
    assert times(["--json", ms], monkeypatch, pure) == ["1767225600.146", "1767225600.167"]


@BOTH
def test_noise_json_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = tmp_path / "noise.pcap"
    out = struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147)
    for at, data in [(5, b"\xff\xfe\xfd"), (20_000_007, rtu("01 03 0000 0001"))]:
        out += struct.pack("<IIII", START, at, len(data), len(data)) + data
    path.write_bytes(out)
    assert times(["--json", str(path)], monkeypatch, pure) == ["1767225600.000000005", "1767225600.020000007"]


@BOTH
def test_watch_json_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = tmp_path / "ns.pcap"
    out = struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147)
    for at, data in [(0, rtu("01 03 0000 0001")), (10_000_001, rtu("01 03 02 0007")),
                     (500_000_000, rtu("01 03 0000 0001")), (510_000_123, rtu("01 03 02 0009"))]:
        out += struct.pack("<IIII", START, at, len(data), len(data)) + data
    path.write_bytes(out)
    use_engine(monkeypatch, pure)
    status, text, err = run_cli(["--watch", "0", "--json", str(path)])
    assert (status, err) == (0, "")
    assert text.splitlines() == ['{"time": 1767225600.510000123, "time_relative": 0.510000123, "frame": 4, '
                                 '"slave": 1, "address": 0, "code": null, "old": "7", "new": "9", "unit": null}']
