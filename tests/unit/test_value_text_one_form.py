"""A value is named one way in --stats' `last`, --report's table of parameters with a single value and
--watch: as the summary names it (the map's text for the word: `IO (I/O profile)`, the ATV71 map's
`3=IO (I/O profile)`). The report and --watch said `3 IO (I/O profile)` where --stats and the summary
said `IO (I/O profile)`; a status word read once was `561 Ready to switch on, ...` in the report (its
word in decimal) where --stats said the bits' names. --watch keeps a status word as the manuals write
it, `16#0231 (...)` (README)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, stats_section, use_engine

# ATV71 slave 12: CHCF (8401) read twice, 3; ETA (3201) read once, 16#0231; COP (8402) read, 2, then
# written 3 (FC6, echoed).
FRAMES = ["0C03 20D1 0001", "0C03 02 0003", "0C03 20D1 0001", "0C03 02 0003",
          "0C03 0C81 0001", "0C03 02 0231",
          "0C03 20D2 0001", "0C03 02 0002", "0C06 20D2 0003", "0C06 20D2 0003"]
ETA = "Ready to switch on, Voltage enabled, Quick stop inactive, Remote"


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    path = tmp_path / "capture.bin"
    path.write_bytes(b"".join(rtu(frame) for frame in FRAMES))
    return path


@pytest.mark.parametrize("pure", [False, True])
def test_stats_report_and_watch_name_a_value_alike(capture: Path, tmp_path: Path,
                                                   monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    code, out, err = run_cli(["--profile", "atv71", "--stats", str(capture)])
    assert code == 0, err
    assert [re.split(r"  +", line.strip()) for line in stats_section(out)[2:5]] == [
        ["12", "3201", "ETA", "1", "0", "0", "0", ETA, "0"],
        ["12", "8401", "CHCF", "2", "0", "0", "0", "IO (I/O profile)", "0"],
        ["12", "8402", "COP", "1", "0", "1", "0", "ALL (command and reference)", "1"],
    ]
    page = tmp_path / "page.html"
    code, _, err = run_cli(["--profile", "atv71", "--report", str(page), str(capture)])
    assert code == 0, err
    table = re.search(r'Parameters with a single value</h3><table class="single">(.*?)</table>',
                      page.read_text()).group(1)
    assert re.findall(r"<tr><td>12</td><td>(\d+)</td><td>\w+</td><td>[^<]*</td><td>([^<]*)</td>", table) == [
        ("3201", ETA), ("8401", "IO (I/O profile)")]
    code, out, err = run_cli(["--profile", "atv71", "--watch", "COP,CHCF,ETA", str(capture)])
    assert (code, out) == (0, "    10            -  12 COP Cd (command) -> ALL (command and reference)\n"), err
    code, out, err = run_cli(["--profile", "atv71", "--watch", "COP", "--json", str(capture)])
    assert code == 0, err
    assert json.loads(out) == {"time": None, "time_relative": None, "frame": 10, "slave": 12, "address": 8402,
                               "code": "COP", "old": "Cd (command)", "new": "ALL (command and reference)",
                               "unit": None}


def test_watch_keeps_a_status_word_as_the_manuals_write_it(tmp_path: Path) -> None:
    capture = tmp_path / "capture.bin"
    capture.write_bytes(b"".join(rtu(frame) for frame in ["0C03 0C81 0001", "0C03 02 0231",
                                                          "0C03 0C81 0001", "0C03 02 0233"]))
    code, out, err = run_cli(["--profile", "atv71", "--watch", "ETA", str(capture)])
    assert (code, out) == (0, "     4            -  12 ETA 16#0231 (Ready to switch on, Voltage enabled, Quick stop "
                              "inactive, Remote) -> 16#0233 (Ready to switch on, Switched on, Voltage enabled, "
                              "Quick stop inactive, Remote)\n"), err
