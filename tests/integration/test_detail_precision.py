"""-V's Arrival time at the capture's precision, as tshark -V shows it (4.0: `Arrival Time: ...
.009018123 UTC`, its `Time since reference or first frame` too): 9 decimals where microseconds cannot
hold the capture's times (a nanosecond pcap, if_tsresol 10^-7 or 2^-10), read from the stamps' integer
nanoseconds. Before, every capture showed 6 (a nanosecond pcap lost its last 3 digits, 2^-10's were
rounded: .163086 of tshark's .163085937). Microsecond and coarser decimal captures keep 6."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_harness import ensure_tool
from test_time_precision import BOTH, NANOS, RESOLUTIONS, START, pcap, pcapng


def arrivals(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> list[str]:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-V", *argv])
    assert (status, err) == (0, "")
    return [line for line in out.splitlines() if "Arrival time" in line]


@BOTH
def test_nanosecond_pcap_arrival_nine_decimals(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcap(tmp_path / "ns.pcap", 10**9, NANOS))
    assert arrivals([path], monkeypatch, pure) == [
        "    Arrival time: 2026-01-01 00:00:00.009018123 UTC (0.000000000 s since the first item)",
        "    Arrival time: 2026-01-01 00:00:00.022017123 UTC (0.012999000 s since the first item)",
    ]  # (was .009018 and 0.012999)
    # each frame alone (-Y), a hex dump with it: the same lines
    assert arrivals(["-x", "-Y", 'kind == "response"', path], monkeypatch, pure) == [
        "    Arrival time: 2026-01-01 00:00:00.022017123 UTC (0.012999000 s since the first item)"]


@BOTH
def test_binary_resolution_not_rounded(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcapng(tmp_path / "b10.pcapng", 0x80 | 10, [START * 1024 + 146, START * 1024 + 167]))
    assert arrivals([path], monkeypatch, pure) == [
        "    Arrival time: 2026-01-01 00:00:00.142578125 UTC (0.000000000 s since the first item)",
        "    Arrival time: 2026-01-01 00:00:00.163085937 UTC (0.020507812 s since the first item)",
    ]  # (was .163086 and 0.020508)


@BOTH
def test_microsecond_pcap_keeps_six(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = str(pcap(tmp_path / "us.pcap", 10**6, [START * 10**6 + 9_018, START * 10**6 + 22_017]))
    assert arrivals([path], monkeypatch, pure) == [
        "    Arrival time: 2026-01-01 00:00:00.009018 UTC (0.000000 s since the first item)",
        "    Arrival time: 2026-01-01 00:00:00.022017 UTC (0.012999 s since the first item)",
    ]


def test_terminal_tree_at_nine_decimals(tmp_path: Path) -> None:
    """A terminal's -V tree (detail_tree) takes the same decimals as the plain text."""
    from dissector.render.detail import detail_tree, render_plain
    from dissector.render.detail_plain import detail_text
    from dissector.model import Stamp
    from dissector.pipeline import dissect_bytes

    from helpers import rtu

    frame = dissect_bytes(rtu("01 03 0000 0001"))[0]
    frame.time = Stamp(NANOS[1])
    first = Stamp(NANOS[0])
    line = "    Arrival time: 2026-01-01 00:00:00.022017123 UTC (0.012999000 s since the first item)"
    assert render_plain(detail_tree(frame, first, 9)).splitlines()[1] == line
    assert detail_text(frame, first, 9).splitlines()[1] == line


def test_arrival_time_as_tshark(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every resolution: tshark -V's 9 digits where we show 9; else the first 6 of them (its zeros)."""
    ensure_tool("tshark", "tshark")  # (a missing tool fails, never skips)
    for tsresol in RESOLUTIONS:
        units = 2 ** (tsresol & 0x7F) if tsresol & 0x80 else 10**tsresol
        first = START * units + units // 7
        path = str(pcapng(tmp_path / f"{tsresol}.pcapng", tsresol, [first, first + units // 50 + 1]))
        theirs = subprocess.run(["tshark", "-r", path, "-V"], capture_output=True, text=True, check=True).stdout
        stamps = re.findall(r"Arrival Time: .* \d\d:\d\d:(\d\d\.\d{9}) UTC", theirs)
        since = re.findall(r"Time since reference or first frame: (\d+\.\d{9}) seconds", theirs)
        ours = [re.search(r":(\d\d\.\d+) UTC \((\d+\.\d+) s since", line).groups()
                for line in arrivals([path], monkeypatch, True)]
        digits = len(ours[0][0]) - 3
        assert digits == (9 if units > 10**6 or 10**6 % units else 6), tsresol
        assert ours == [(stamp[: 3 + digits], gap[: len(gap) - 9 + digits]) for stamp, gap in zip(stamps, since)], tsresol
