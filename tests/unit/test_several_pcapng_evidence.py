"""Several pcapng files with packets from several interfaces: each interface is one bus over every file that
has it (render/buses.py), and each file's interface numbers its frames from 1 under its own title, as the
summary shows it (`==> a.pcapng: /dev/ttyS0 <==`). The evidence cited of such a bus names that title as
files read as one bus name their file (35054b7, 0288417): profile `auto`'s reason, --watch's lines, the
parameter memory's note, the report's frames, the outages. Before, only outages did: the reason said "in
frame #2" (a.pcapng's; b.pcapng's frame 2 is the exception), --watch had no file. One file of several
interfaces cites by number alone, as before. Compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, stats_section, use_engine
from test_pcapng_interfaces import _pcapng

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
IDENT = [rtu("02 2B 0E 01 00"),
         rtu("02 2B 0E 01 02 00 00 02 00 0D" + b"Telemecanique".hex() + "01 0B" + b"ATV71HU15M3".hex())]
CHCF = [rtu("02 03 20D1 0001"), rtu("02 03 02 0003")]
REFUSED = [rtu("02 03 20D1 0001"), rtu("02 83 02")]
LOST = [rtu("02 03 0C81 0001"), rtu("02 03 0C81 0001"), rtu("02 03 0C81 0001"), rtu("02 03 02 0001")]
POLL = [rtu("03 04 0000 0001"), rtu("03 04 02 0007")]
A0, B0 = "a.pcapng: /dev/ttyS0", "b.pcapng: /dev/ttyS0"


def _packets(interface: int, frames: list[bytes], start: int) -> list[tuple[int, int, bytes]]:
    """A frame every 30 ms, 1.5 s after an unanswered request (past the default timeout, 1 s)."""
    found, micros = [], start
    for before, frame in zip([None, *frames], frames):
        micros += 1_500_000 if before == frame else 30_000
        found.append((interface, micros, frame))
    return found


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """ttyS0: a.pcapng identifies the drive (frame 2) and reads CHCF 3 (frame 4); b.pcapng's CHCF read is
    refused (frame 2), then slave 2 misses two requests (frames 3, 4). ttyS1: slave 3 polled in each."""
    monkeypatch.chdir(tmp_path)
    names = ["/dev/ttyS0", "/dev/ttyS1"]
    for name, frames, start in (("a.pcapng", IDENT + CHCF, 0), ("b.pcapng", REFUSED + LOST, 60_000_000)):
        packets = _packets(0, frames, start) + _packets(1, POLL, start + 5_000)
        (tmp_path / name).write_bytes(_pcapng(names, sorted(packets, key=lambda packet: packet[1])))
    return ["a.pcapng", "b.pcapng"]


@BOTH
def test_stats_cite_the_input(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", *files])
    assert status == 0, err
    reason = f"Read Device Identification in frame #2 of {A0}: ProductCode 'ATV71HU15M3'"
    assert stats_section(out, "Device profiles")[2] == f"    2  atv71    {reason}"
    assert f"  slave 2 silent 60.060000 - 61.560000, 2 requests unanswered (frames 3..4 of {B0})" in out
    status, out, err = run_cli(["--stats", "--json", *files])
    profiles = json.loads(out.splitlines()[0])["profiles"]
    assert profiles == [{"slave": 2, "profile": "atv71", "reason": reason, "frame": 2, "file": A0}]


@BOTH
def test_memory_and_watch_cite_the_input(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(files)
    assert status == 0, err
    refused = next(line for line in out.splitlines() if line.startswith("     2") and "exception" in line)
    assert f"[CHCF (8401) became protected: read 3 in frame #4 of {A0}, exception 02 now]" in refused
    status, out, err = run_cli(["--watch", "CHCF", *files])
    assert status == 0, err
    assert out.splitlines() == [
        f"==> {B0} <==",
        "     2    60.030000   2 CHCF IO (I/O profile) -> protected (exception 02)",
    ]
    status, out, err = run_cli(["--watch", "CHCF", "--json", *files])
    assert [(change["frame"], change["file"]) for change in map(json.loads, out.splitlines())] == [(2, B0)]


@BOTH
def test_report_cites_the_input(files: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, _out, err = run_cli([*files, "--report", str(tmp_path / "bus.html")])
    assert status == 0, err
    text = (tmp_path / "bus.html").read_text(encoding="utf-8")
    assert f"<td>60.030000 #2 of {B0}</td>" in text  # (the refused read, in the events table)
    assert f"<td>#3..#4 of {B0}</td>" in text  # (the outage)
    pages = re.findall(r'<script type="application/json" id="report-data-[01]">(.*?)</script>', text, re.S)
    assert [json.loads(page)["inputs"] for page in pages] == [
        [[0, A0], [4, B0]], [[0, "a.pcapng: /dev/ttyS1"], [2, "b.pcapng: /dev/ttyS1"]]]


def test_one_file_cites_the_number_alone(files: list[str]) -> None:
    status, out, err = run_cli(["--stats", files[0]])
    assert status == 0, err
    assert stats_section(out, "Device profiles")[2] == (
        "    2  atv71    Read Device Identification in frame #2: ProductCode 'ATV71HU15M3'")
    status, out, err = run_cli(["--watch", "CHCF", files[1]])
    assert "of " not in out
