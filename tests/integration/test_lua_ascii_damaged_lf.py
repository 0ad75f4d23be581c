"""The plugin reads a Modbus ASCII line ended by CR and a byte other than LF as vw3-decode does
(tests/unit/test_ascii_damaged_lf.py): the 08/03 echo that already ends with the new character is a frame and
the character ends the later lines (before: noise from the echo on, "ASCII frame cut short by the next ':'");
any other byte there is a damaged LF, a frame with a warning naming it (before: noise). Real tshark with
-X lua_script:lua/vw3.lua, -2, the bytes in one record (its frames' request_frame: record 1) and a line a record."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_ascii_damaged_lf import ANSWER, CASES, CHANGE, DAMAGED, NOT_SET, REQUEST  # noqa: E402

pytestmark = pytest.mark.integration

T0 = 1767225600.0
FIELDS = ["-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "vw3.kind", "-e", "vw3.request_frame",
          "-e", "vw3.warning", "-e", "vw3.noise.reason", "-e", "_ws.col.Info"]
READ, SET = "17 Read Holding Registers", "17 Diagnostics {} 03h Change ASCII Input Delimiter = 8448"
# (kinds, request frames, warnings, Info) of the one record holding each case: -2 reads it as a file, profile
# `auto`'s choice final as vw3-decode FILE's, no frame [provisional]
SHOWN = {
    "08/03 echo ending with the new character": (
        "1,2,1,2", "1,1", "", [SET.format("request"), SET.format("response"), f"{READ} request 0",
                               f"{READ} response 0"]),
    "a damaged LF": ("1,2,1,2", "1,1", DAMAGED.format(0x0B), [f"{READ} request 0", f"{READ} response 0"] * 2),
    "a damaged LF at the end of the capture": (
        "1,2", "1", DAMAGED.format(0x0B), [f"{READ} request 0", f"{READ} response 0"]),
    "a damaged LF and a bad LRC": (
        "1,2,1,2", "1,1", DAMAGED.format(0x0B), [f"{READ} request 0", f"{READ} response 0 BAD LRC",
                                                 f"{READ} request 0", f"{READ} response 0"]),
    "another delimiter than the one 08/03 set": (
        "1,2,1,2", "1,1", NOT_SET.format(0x23), [SET.format("request"), SET.format("response"),
                                                 f"{READ} request 0", f"{READ} response 0"]),
}


def tshark(pcap: Path) -> list[str]:
    result = run_tshark(pcap, *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("case", list(CASES))
def test_one_record(case: str, tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", [(CASES[case][0], T0)])
    kinds, requests, warnings, info = SHOWN[case]
    shown = "; ".join(info)
    assert tshark(pcap) == [f"{kinds}|{requests}|{warnings}||{shown}"]


def test_a_line_a_record(tmp_path: Path) -> None:
    lines = [CHANGE + b"\r\n", CHANGE + b"\r!", REQUEST + b"\r!", ANSWER + b"\r!", REQUEST + b"\r!",
             ANSWER + b"\r\x0b"]
    pcap = write_pcap(tmp_path / "lines.pcap", [(line, T0 + index * 0.01) for index, line in enumerate(lines)])
    assert tshark(pcap) == [
        f"1||||{SET.format('request')}", f"2|1|||{SET.format('response')}", f"1||||{READ} request 0",
        f"2|3|||{READ} response 0", f"1||||{READ} request 0",
        f"2|5|{DAMAGED.format(0x0B)}||{READ} response 0"]
