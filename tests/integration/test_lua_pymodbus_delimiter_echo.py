"""The plugin follows pymodbus's FC8/03 (Change ASCII Input Delimiter) as vw3-decode does
(tests/unit/test_pymodbus_delimiter_echo.py, peer69): the echo of data 0021 makes CR 00 its slave's line end, so
the lines after it carry no warning (before: each warned `line ends with CR then 00h where LF belongs`). Real
tshark with -X lua_script:lua/vw3.lua, -2, a line a record."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_pymodbus_delimiter_echo import BAD_DATA, LINES  # noqa: E402

pytestmark = pytest.mark.integration

T0 = 1796688688.0
FIELDS = ["-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "vw3.kind", "-e", "vw3.request_frame",
          "-e", "vw3.warning", "-e", "vw3.noise.reason", "-e", "_ws.col.Info"]
READ, ANSWER = "5 Read Holding Registers request", "5 Read Holding Registers response"
SHOWN = [f"1||||{READ} 1..2 (2)", f"2|1|||{ANSWER} 1..2 (2)",
         f"1||{BAD_DATA}||5 Diagnostics request 03h Change ASCII Input Delimiter = 33",
         "2|3|||5 Diagnostics response 03h Change ASCII Input Delimiter = 33",
         f"1||||{READ} 1..2 (2)", f"2|5|||{ANSWER} 1..2 (2)", f"1||||{READ} 2", f"2|7|||{ANSWER} 2"]


def test_a_line_a_record(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "lines.pcap", [(data, T0 + index * 0.05) for index, data in enumerate(LINES)])
    result = run_tshark(pcap, "-n", *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == SHOWN
