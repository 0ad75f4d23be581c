"""The report's health additions (issue 29): grouped events, response times over time, outages, written
parameters, `wrote FILE` on a terminal."""
from __future__ import annotations

import io
import json
import re
from pathlib import Path

from conftest import ROOT
from dissector.app.cli import Environment, run
from dissector.render.report.groups import EventGroups

CAPTURES = ROOT / "captures"


def test_groups_count_first_and_last_and_ignore_varying_numbers() -> None:
    groups = EventGroups()
    groups.add("noise", None, "4 bytes of noise at offset 0", 1.0, 1)
    groups.add("exception", 12, "exception 02 to function 3", 2.0, 10)
    groups.add("noise", None, "5 bytes of noise at offset 307", 3.0, 34)
    groups.add("exception", 12, "exception 02 to function 3", 4.0, 12)
    groups.add("exception", 12, "exception 03 to function 3", 5.0, 14)
    rows = [(g.kind, g.slave, g.label, g.count, g.first_frame, g.last_frame) for g in groups.rows()]
    assert rows == [
        # (the review of issue 29: `4 bytes of noise at offset 0`, count 2, named one run of two)
        ("noise", None, "4..5 bytes of noise at offset 0..307", 2, 1, 34),
        ("exception", 12, "exception 02 to function 3", 2, 10, 12),
        ("exception", 12, "exception 03 to function 3", 1, 14, 14),
    ]
    groups.add("silence", 1, "silence of 2.000 ms inside the frame before byte 4", 1.0, 3)
    groups.add("silence", 1, "silence of 3.5 ms inside the frame before byte 4", 2.0, 7)
    groups.add("silence", 1, "silence of 1.25 ms inside the frame before byte 4", 3.0, 9)
    (silence,) = [group for group in groups.rows() if group.kind == "silence"]
    assert (silence.label, silence.count) == ("silence of 1.25..3.5 ms inside the frame before byte 4", 3)


def _report(tmp_path: Path, capture: str, *argv: str, stderr_tty: bool = False) -> tuple[str, str]:
    page = tmp_path / "r.html"
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BytesIO(), out, err, stdout_isatty=False, stderr_isatty=stderr_tty)
    assert run([str(CAPTURES / capture), "--report", str(page), *argv], env) == 0
    return page.read_text(), err.getvalue()


def _data(page: str) -> dict:
    return json.loads(re.search(r'<script type="application/json" id="report-data">(.*?)</script>', page, re.S).group(1))


def test_noisy_bus_outage_is_a_band_of_slave_5(tmp_path: Path) -> None:
    page, err = _report(tmp_path, "noisy_bus.pcap")
    assert err == ""
    data = _data(page)
    (outage,) = data["outages"]
    assert (outage["slave"], outage["requests"], outage["first_frame"], outage["last_frame"]) == (5, 2, 28, 29)
    assert (outage["x0"], outage["x1"]) == (0.839570, 1.050219)  # seconds after the first item
    assert [(entry["slave"], entry["answers"]) for entry in data["responses"]] == [(1, 8), (5, 0), (12, 8)]
    assert max(data["responses"][0]["y"]) == 13.304 and data["clock"] == "r"
    assert "<td>5</td><td>0.839570</td><td>1.050219</td><td>2</td><td>#28..#29</td>" in page
    assert "<td>inter-frame gaps</td><td>2-5 ms: 8, 5-10 ms: 19, 10-20 ms: 2, 100-200 ms: 6, 200-500 ms: 2</td>" in page
    # Two noise runs and their different lengths and offsets: one group of 2.
    assert "<td>noise</td><td></td><td>4..5 bytes of noise at offset 0..307</td><td>2</td><td>0.000000 #1</td><td>1.407727 #34</td>" in page


def test_time_format_and_written_parameters(tmp_path: Path) -> None:
    page, _err = _report(tmp_path, "atv71_commissioning.pcap", "-t", "ud")
    data = _data(page)
    assert data["clock"] == "ud"
    # HSP, CHCF, FR1, CD1 (FC6), CMD, LFR (FC23's write half), ACC, DEC (FC16); not RFR, only read.
    assert data["written"] == ["2:3104", "2:8401", "2:8413", "2:8423", "2:8501", "2:8502", "2:9001", "2:9002"]
    assert "<td>exception</td><td>2</td><td>exception 07 to function 6" in page
    assert "</td><td>1</td><td>2026-01-01 00:00:01.346013 #64</td><td></td>" in page


def test_wrote_the_file_on_a_terminal_only(tmp_path: Path) -> None:
    _page, err = _report(tmp_path, "p38_protection.pcap", stderr_tty=True)
    assert err.endswith(f"vw3-decode: wrote {tmp_path / 'r.html'}\n")
    assert _report(tmp_path, "p38_protection.pcap")[1] == ""
