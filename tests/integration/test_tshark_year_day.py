"""tshark 4.0's -t adoy and -t udoy (its help: a|ad|adoy|d|dd|e|r|u|ud|udoy): the date as year/day of the
year, `2026/001 00:00:00.019272`. Before, vw3-decode refused them: "argument -t: invalid choice: 'udoy'"."""
from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import ensure_tool

ROOT = Path(__file__).resolve().parents[2]
P38 = str(ROOT / "captures" / "p38_protection.pcap")
COLUMNS = re.compile(r" *\d+ +(.+?) +(?:\d{1,3}|-) (?:request|response|exception|noise)")


@pytest.mark.parametrize(("fmt", "zone", "expected"), [
    ("udoy", "Europe/Paris", ["2026/001 00:00:00.019272", "2026/001 00:00:00.535368"]),
    ("adoy", "Europe/Paris", ["2026/001 01:00:00.019272", "2026/001 01:00:00.535368"]),  # UTC+1 in January
    ("adoy", "America/New_York", ["2025/365 19:00:00.019272", "2025/365 19:00:00.535368"]),  # the day before
])
def test_year_and_day_of_the_year_as_tshark(fmt: str, zone: str, expected: list[str],
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    tshark = subprocess.run([ensure_tool("tshark", "tshark"), "-r", P38, "-t", fmt, "-Y",
                             "frame.number >= 2 && frame.number <= 3", "-T", "fields", "-e", "_ws.col.Time"],
                            capture_output=True, text=True, timeout=120, env=dict(os.environ, TZ=zone))
    assert tshark.returncode == 0, tshark.stderr
    assert tshark.stdout.splitlines() == expected
    monkeypatch.setenv("TZ", zone)
    import time
    time.tzset()
    try:
        status, out, err = run_cli(["-t", fmt, "-Y", "frame >= 2 and frame <= 3", P38])
    finally:
        monkeypatch.undo()
        time.tzset()
    assert (status, err) == (0, "")
    assert [COLUMNS.match(line).group(1) for line in out.splitlines()] == expected  # type: ignore[union-attr]
