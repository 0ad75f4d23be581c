"""Several timed files read as one bus (`vw3-decode --stats t1.pcap t2.pcap`, --report) number their frames
each from 1, as the summary shows them under each `==> FILE <==`. The bus's outages were listed by that
per-file number with no file named (t2.pcap's `(frames 1..2)` before t1.pcap's `(frames 7..8)`), and the
poll cycle's rows were ordered by it too (t2.pcap's first key before t1.pcap's second). Now both are in the
order of time (file, then frame) and an outage cites its frames with their file; one file prints as before.
Compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, run_cli, stats_section, use_engine

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1767225600.0
A, A_ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")
C, C_ANSWER = rtu("01 03 0010 0001"), rtu("01 03 02 0009")
B, B_ANSWER = rtu("02 04 0000 0002"), rtu("02 04 04 0001 0002")
# t1.pcap: C, A, A answered (frames 1..6), A and A unanswered (7, 8: slave 1's outage), A answered, C twice.
T1 = [C, C_ANSWER, A, A_ANSWER, A, A_ANSWER, A, A, A, A_ANSWER, C, C_ANSWER, C, C_ANSWER]
# t2.pcap, a minute later: B and B unanswered (frames 1, 2: slave 2's outage), B answered.
T2 = [B, B, B, B_ANSWER]


def _pcap(path: Path, frames: list[bytes], start: float) -> None:
    with open(path, "wb") as stream:
        writer = PcapWriter(stream)
        milliseconds = 0  # (whole: the times are exact)
        for frame in frames:
            milliseconds += 10 if frame in (A_ANSWER, B_ANSWER, C_ANSWER) else 100
            writer.write(frame, start + milliseconds / 1000)
        writer.close()


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    monkeypatch.chdir(tmp_path)
    _pcap(tmp_path / "t1.pcap", T1, T0)
    _pcap(tmp_path / "t2.pcap", T2, T0 + 60)
    return ["t1.pcap", "t2.pcap"]


def _outage_lines(out: str) -> list[str]:
    lines = out.splitlines()
    start = lines.index("outages (two or more consecutive requests unanswered)")
    end = start + 1
    while end < len(lines) and lines[end].startswith("  slave "):
        end += 1
    return lines[start + 1:end]


@BOTH
def test_stats_outages_by_time_with_their_file(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", *files])
    assert status == 0, err
    assert _outage_lines(out) == [
        "  slave 1 silent 0.330000 - 0.430000, 2 requests unanswered (frames 7..8 of t1.pcap)",
        "  slave 2 silent 60.000000 - 60.100000, 2 requests unanswered (frames 1..2 of t2.pcap)",
    ]
    status, out, err = run_cli(["--stats", "--json", *files])
    assert status == 0, err
    assert [(entry["slave"], entry["first_frame"], entry["last_frame"], entry["file"], entry["last_file"])
            for entry in json.loads(out)["bus"]["outages"]] == [(1, 7, 8, "t1.pcap", "t1.pcap"),
                                                               (2, 1, 2, "t2.pcap", "t2.pcap")]


@BOTH
def test_stats_poll_cycle_by_time(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", "--json", *files])
    assert status == 0, err
    assert [(row["slave"], row["function"], row["start"], row["count"])
            for row in json.loads(out)["poll_cycle"]] == [(1, 3, 16, 3), (1, 3, 0, 5), (2, 4, 0, 3)]


@BOTH
def test_report_outages_by_time_with_their_file(files: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--report", "r.html", *files])
    assert (status, out, err) == (0, "", "")
    page = (tmp_path / "r.html").read_text(encoding="utf-8")
    table = re.search(r"<h3>Outages.*?<tbody>(.*?)</tbody>", page, re.S)
    assert table is not None
    assert re.findall(r"<tr><td>(\d+)</td>.*?<td>([^<]*)</td></tr>", table.group(1)) == [
        ("1", "#7..#8 of t1.pcap"), ("2", "#1..#2 of t2.pcap")]
    assert re.findall(r"<tr><td>\d+</td><td>[^<]*</td>", page[page.index('id="poll"'):])[:3] == [
        "<tr><td>1</td><td>3 Read Holding Registers</td>", "<tr><td>1</td><td>3 Read Holding Registers</td>",
        "<tr><td>2</td><td>4 Read Input Registers</td>"]


def test_one_file_as_before(files: list[str]) -> None:
    status, out, err = run_cli(["--stats", "t1.pcap"])
    assert status == 0, err
    assert _outage_lines(out) == [
        "  slave 1 silent 0.330000 - 0.430000, 2 requests unanswered (frames 7..8)"]
    status, out, err = run_cli(["--stats", "--json", "t1.pcap"])
    assert json.loads(out)["bus"]["outages"] == [{"slave": 1, "start": T0 + 0.43, "end": T0 + 0.53, "requests": 2,
                                                  "first_frame": 7, "last_frame": 8}]


@BOTH
def test_an_outage_over_two_files_cites_both(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """s1.pcap ends with two requests unanswered and an FC8 04 (Force Listen Only Mode: no answer awaited, so
    it neither counts nor ends the run); s2.pcap begins with two more: one outage of four, from s1.pcap's
    frame 3 to s2.pcap's frame 2 (it said "frames 3..2")."""
    use_engine(monkeypatch, pure)
    monkeypatch.chdir(tmp_path)
    _pcap(tmp_path / "s1.pcap", [A, A_ANSWER, A, A, rtu("01 08 0004 0000")], T0)
    _pcap(tmp_path / "s2.pcap", [A, A, A, A_ANSWER], T0 + 60)
    status, out, err = run_cli(["--stats", "s1.pcap", "s2.pcap"])
    assert status == 0, err
    assert _outage_lines(out) == [
        "  slave 1 silent 0.110000 - 60.100000, 4 requests unanswered (frames 3 of s1.pcap..2 of s2.pcap)"]
