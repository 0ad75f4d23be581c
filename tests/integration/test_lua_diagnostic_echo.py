"""The plugin warns of an FC8 answer that should repeat its request's data and does not, as vw3-decode does
(tests/unit/test_diagnostic_echo.py): real tshark with -X lua_script:lua/vw3.lua, -2 and one pass; the first
request again (a polled request's decoding is kept by its bytes) answered with other data again."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_diagnostic_echo import ECHO, FRAMES  # noqa: E402

pytestmark = pytest.mark.integration

INFO = ["00h Return Query Data = 4660", "00h Return Query Data = 22136", "00h Return Query Data = 42405",
        "00h Return Query Data = 42405", "00h Return Query Data data 01020304", "00h Return Query Data data 01020305",
        "01h Restart Communications Option = 0", "01h Restart Communications Option = 65280",
        "0Bh Return Bus Message Count = 0", "0Bh Return Bus Message Count = 7",
        "0Ah Clear Counters and Diagnostic Register = 0", "0Ah Clear Counters and Diagnostic Register = 0",
        "00h Return Query Data = 4660", "00h Return Query Data = 22136"]
WARNED = {2, 6, 8, 14}


@pytest.mark.parametrize("two_pass", [True, False])
def test_an_answer_with_other_data_is_warned(tmp_path: Path, two_pass: bool) -> None:
    frames = FRAMES + FRAMES[:2]
    pcap = write_pcap(tmp_path / "diagnostics.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                      for index, frame in enumerate(frames)])
    got = run_tshark(pcap, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e", "vw3.warning",
                     "-e", "_ws.col.Info", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    tail = "" if two_pass else " [provisional]"  # (one pass: profile auto has not seen the whole capture)
    assert got.stdout.splitlines() == [
        f"{number}|{ECHO if number in WARNED else ''}|1 Diagnostics {'response' if number % 2 == 0 else 'request'} "
        f"{info}{tail}" for number, info in enumerate(INFO, 1)]
