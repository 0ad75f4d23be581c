"""--stats' bus timing and the --report page of an input that gave no item: a pcap of empty records (each
timed), a pcap with no record, an empty raw file. They said `no timestamps in this input: ... need a pcap,
pcapng or timed dump` of a pcap with times; now what is true: no bytes, nothing to measure. An input whose
items have no times (a raw .bin) still says `no timestamps`; a timed pcap of noise only has its timing."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_harness import write_pcap

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1767225600.0
LINE = "line: 19200 baud (assumed: --baud sets it), 11 bits a character, t3.5 2.005 ms, timeout 1000 ms"
UNHEARD = "no bytes in this input (no frame, no noise): no load, gaps, turnaround or outages to measure"
UNTIMED = "no timestamps in this input: load, gaps, turnaround and outages need a pcap, pcapng or timed dump"
NOTHING = "0 frames, 0 noise bytes in 0 runs"


def _inputs(tmp_path: Path) -> dict[str, Path]:
    raw = tmp_path / "empty.bin"
    raw.write_bytes(b"")
    return {
        "empty records": write_pcap(tmp_path / "empty.pcap", [(b"", T0 + 0.01 * index) for index in range(1000)]),
        "no record": write_pcap(tmp_path / "zero.pcap", []),
        "empty file": raw,
    }


def _bus_timing(out: str) -> list[str]:
    return out[out.index("\nBus timing\n") + 1:].splitlines()


@BOTH
def test_stats_of_nothing_says_no_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    for name, path in _inputs(tmp_path).items():
        status, out, _err = run_cli(["--stats", str(path)])
        assert status == 0, name
        assert out.splitlines()[0] == NOTHING, name
        assert _bus_timing(out) == ["Bus timing", LINE, UNHEARD], name
        status, out, _err = run_cli(["--stats", "--json", str(path)])
        bus = json.loads(out)["bus"]
        assert (bus["timed"], bus["span"], bus["load"], bus["gaps"], bus["outages"]) == (False, None, None, None, []), name


@BOTH
def test_report_of_nothing_says_no_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    for name, path in _inputs(tmp_path).items():
        page = tmp_path / "r.html"
        status, _out, _err = run_cli(["--report", str(page), str(path)])
        assert status == 0, name
        text = page.read_text(encoding="utf-8")
        assert re.findall(r'<p class="summary">(.*?)</p>', text) == [NOTHING], name
        assert re.findall(r'<h2 id="bus">Bus</h2>\n(<p>.*?</p>)', text) == [
            "<p>No bytes in this input (no frame, no noise): no load, gaps, turnaround or outages to measure.</p>"
        ], name


@BOTH
def test_untimed_bytes_still_say_no_timestamps(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    raw = tmp_path / "noise.bin"
    raw.write_bytes(bytes.fromhex("ff00aa") * 10)
    status, out, _err = run_cli(["--stats", str(raw)])
    assert status == 0
    assert _bus_timing(out) == ["Bus timing", LINE, UNTIMED]
    page = tmp_path / "r.html"
    assert run_cli(["--report", str(page), str(raw)])[0] == 0
    text = page.read_text(encoding="utf-8")
    assert re.findall(r'<p class="summary">(.*?)</p>', text) == [
        "0 frames, 30 noise bytes in 1 run, no timestamps (x axis: frame number)"]
    assert re.findall(r'<h2 id="bus">Bus</h2>\n(<p>.*?</p>)', text) == [
        "<p>No timestamps in this capture: load, gaps, turnaround and outages need a pcap, pcapng or timed dump.</p>"
    ]


@BOTH
def test_timed_noise_has_its_timing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    # One record of 30 noise bytes: 30 x 11 bits at 19200 baud = 17.1875 ms, the line busy throughout.
    path = write_pcap(tmp_path / "noise.pcap", [(bytes.fromhex("ff00aa") * 10, T0)])
    status, out, _err = run_cli(["--stats", str(path)])
    assert status == 0
    assert _bus_timing(out) == ["Bus timing", LINE, "load: 100.0 %", "outages: none"]
    bus = json.loads(run_cli(["--stats", "--json", str(path)])[1])["bus"]
    assert (bus["timed"], bus["span"], bus["gaps"], bus["outages"]) == (True, 0.017188, None, [])
