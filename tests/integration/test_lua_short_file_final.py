"""tshark -2 on a short file: profile auto's choice is final in the second pass, as vw3-decode's is for a
file (hunt 69, defect 1). A file of one record (and one whose last record is empty) was shown
`[provisional]` (vw3.provisional 1) under -2: the plugin ended its first pass only when Wireshark dissected
again a record older than the newest, which a one-record file never has. tshark dissects a record again only
in -2's second pass, so there the newest ends the first pass too. One pass (a live capture) still says
provisional, as vw3-decode reading standard input. Real tshark 4.0 with -X lua_script:lua/vw3.lua."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import ROOT, lua_errors, lua_items, place_items, record_lengths, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0  # 2026-01-01 00:00:00 UTC
REQUEST = "01 03 0000 0002"
ANSWER = "01 03 04 0001 0002"
INFO_REQUEST = "1 Read Holding Registers request 0..1 (2)"
INFO_ANSWER = "1 Read Holding Registers response 0..1 (2)"

# (records, the plugin's (frame.number, vw3.provisional, Info) under -2)
CASES = {
    "one record": ([REQUEST], [("1", "", INFO_REQUEST)]),
    "one frame, an empty record": ([REQUEST, ""], [("1", "", INFO_REQUEST), ("2", "", "")]),
    "two records (unchanged)": ([REQUEST, ANSWER], [("1", "", INFO_REQUEST), ("2", "", INFO_ANSWER)]),
}


def _pcap(tmp_path: Path, records: list[str]) -> Path:
    return write_pcap(tmp_path / "short.pcap",
                      [(rtu(text) if text else b"", T0 + index) for index, text in enumerate(records)])


def _shown(pcap: Path, two_pass: bool) -> list[tuple[str, ...]]:
    result = run_tshark(pcap, "-T", "fields", "-e", "frame.number", "-e", "vw3.provisional", "-e", "_ws.col.Info",
                        two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr
    return [tuple(line.split("\t")) for line in result.stdout.splitlines()]


def _decoded(pcap: Path, stdin: bool) -> list[dict[str, object]]:
    """vw3-decode --json: the file (read twice, its choices final), or standard input (read once)."""
    run = subprocess.run([sys.executable, "-m", "dissector", "-" if stdin else str(pcap), "--json"],
                         input=pcap.read_bytes(), capture_output=True, cwd=ROOT, timeout=300, check=True)
    return [json.loads(line) for line in run.stdout.decode().splitlines()]


@pytest.mark.parametrize("name", sorted(CASES))
def test_two_pass_short_file_is_final_as_vw3_decode_file(tmp_path: Path, name: str) -> None:
    records, expected = CASES[name]
    pcap = _pcap(tmp_path, records)
    assert _shown(pcap, two_pass=True) == expected
    # vw3-decode reading the file: no frame provisional, item for item what the plugin shows under -2
    decoded = _decoded(pcap, stdin=False)
    assert [item.get("provisional", False) for item in decoded] == [False] * len(decoded)
    lua, _, _ = lua_items(pcap)
    assert compare(place_items(decoded, record_lengths(pcap)), lua) == []


@pytest.mark.parametrize("name", sorted(CASES))
def test_one_pass_stays_provisional_as_vw3_decode_stdin(tmp_path: Path, name: str) -> None:
    records, expected = CASES[name]
    pcap = _pcap(tmp_path, records)
    once = [(number, "1" if info else "", f"{info} [provisional]" if info else "") for number, _, info in expected]
    assert _shown(pcap, two_pass=False) == once
    assert [item.get("provisional") for item in _decoded(pcap, stdin=True)] == [True] * (len(records) - records.count(""))
