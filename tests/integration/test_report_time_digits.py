"""--report's times (the events' first and last, the trend marks) with 9 decimals where microseconds cannot hold
the capture's times (a nanosecond pcap, if_tsresol 2^-10), as -V's Arrival time (timefmt.detail_digits, the
predicate pcapwriter.finer_than_micros), read from the stamps' nanoseconds; a microsecond pcap keeps 6. Before,
every page said 6 (`0.012999 #2` of a nanosecond pcap whose answer came 0.012999000 s after the first item)."""
from __future__ import annotations

import re
import struct
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

START = 1_767_225_600  # 2026-01-01 00:00:00 UTC
# ATV71 (slave 12): 8400 reads 16#8000 (non-existent, a mark), then readable again; two exceptions (events)
FRAMES = [
    (rtu("0C03 20D0 0003"), 9_018_123), (rtu("0C03 06 8000 0003 0002"), 22_017_123),
    (rtu("0C03 20D0 0003"), 509_018_456), (rtu("0C03 06 0001 0003 0002"), 522_017_789),
    (rtu("0C03 0000 0001"), 609_018_000), (rtu("0C83 02"), 622_017_001),
    (rtu("0C03 0000 0001"), 709_018_000), (rtu("0C83 02"), 722_017_999),
]


def pcap(path: Path, units: int) -> Path:
    magic = 0xA1B2C3D4 if units == 10**6 else 0xA1B23C4D
    out = struct.pack("<IHHiIII", magic, 2, 4, 0, 0, 65535, 147)
    for data, ns in FRAMES:
        out += struct.pack("<IIII", *divmod(START * units + ns * units // 10**9, units), len(data), len(data)) + data
    path.write_bytes(out)
    return path


def _block(kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", kind, len(body) + 12) + body + struct.pack("<I", len(body) + 12)


def pcapng_1024(path: Path) -> Path:
    """if_tsresol 2^-10 s: each time cut to a 1/1024 s tick."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    out += _block(1, struct.pack("<HHI", 147, 0, 0) + struct.pack("<HHB3x", 9, 1, 0x80 | 10) + b"\0" * 4)
    for data, ns in FRAMES:
        stamp = START * 1024 + ns * 1024 // 10**9
        out += _block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data)) + data)
    path.write_bytes(out)
    return path


def times(page: str) -> list[str]:
    """The events table's first/last cells and the marks' times, in page order."""
    return re.findall(r"<td>([^<]* #\d+)</td>", page) + re.findall(r'<li class="mark" data-x="[^"]*">(.*?): [a-z]', page)


def report(path: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, *options: str) -> str:
    use_engine(monkeypatch, pure)
    page = tmp_path / "page.html"
    status, _out, err = run_cli(["--profile", "atv71", "--report", str(page), *options, str(path)])
    assert status == 0, err
    return page.read_text(encoding="utf-8")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_nanosecond_pcap_nine_decimals(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    page = report(pcap(tmp_path / "ns.pcap", 10**9), tmp_path, monkeypatch, pure)
    assert times(page) == ["0.012999000 #2", "0.512999666 #4", "0.612998878 #6", "0.712999876 #8", "0.612998878 #6",
                           "0.612998878", "0.012999000", "0.512999666"]  # (-V: 0.012999000 s since the first item)
    # (was 0.012999 #2, 0.513000 #4, 0.612999 #6, 0.713000 #8, ...)
    page = report(pcap(tmp_path / "ns.pcap", 10**9), tmp_path, monkeypatch, pure, "-t", "u")
    assert times(page)[:4] == ["00:00:00.022017123 #2", "00:00:00.522017789 #4", "00:00:00.622017001 #6",
                               "00:00:00.722017999 #8"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_binary_resolution_nine_decimals(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    page = report(pcapng_1024(tmp_path / "b10.pcapng"), tmp_path, monkeypatch, pure)
    assert times(page) == ["0.012695313 #2", "0.512695313 #4", "0.612304688 #6", "0.712890625 #8", "0.612304688 #6",
                           "0.612304688", "0.012695313", "0.512695313"]  # (-V: 0.012695313 s since the first item)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_microsecond_pcap_keeps_six(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    page = report(pcap(tmp_path / "us.pcap", 10**6), tmp_path, monkeypatch, pure)
    assert times(page) == ["0.012999 #2", "0.512999 #4", "0.612999 #6", "0.712999 #8", "0.612999 #6", "0.612999",
                           "0.012999", "0.512999"]
