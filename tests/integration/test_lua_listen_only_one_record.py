"""The plugin reads pymodbus's answer to 08/04 (its sub-function alone: tests/integration/test_listen_only_echo.py)
as vw3-decode does when the 08/04, that answer and the master's repeats come in one record. Before, a Lua error
(`attempt to compare number with nil`, lua/src/pairing.lua): the open 08/04's data length was read after its
bytes had been let go (take_frame), and the record showed no frame at all. RTU and ASCII, tshark -2 and one
pass, against vw3-decode --json (the file; standard input for one pass). Real tshark 4.0 with the plugin."""
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

LISTEN, ANSWERED = "01 08 0004 0000", "01 08 0004"
ECHO = "an answer to 08/04 (Force Listen Only Mode), which the spec's slave does not answer"
# (the RTU answer's 6 bytes are warned of; an ASCII line's length is not its frame's)
WARNINGS = {"rtu": f"frame length 6 disagrees with the spec's layout (8 bytes), its CRC good,{ECHO}", "ascii": ECHO}
REQUEST_INFO = "1 Diagnostics request 04h Force Listen Only Mode = 0"
ANSWER_INFO = "1 Diagnostics response 04h Force Listen Only Mode"


def ascii_frame(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([-sum(body) & 0xFF])).hex().upper().encode() + b"\r\n"


@pytest.mark.parametrize("two_pass", [True, False], ids=["two-pass", "one-pass"])
@pytest.mark.parametrize("mode", ["rtu", "ascii"])
def test_the_answer_in_one_record_with_its_request(tmp_path: Path, mode: str, two_pass: bool) -> None:
    frame = rtu if mode == "rtu" else ascii_frame
    pcap = write_pcap(tmp_path / "one.pcap", [(b"".join(frame(text) for text in [LISTEN, ANSWERED, LISTEN, LISTEN]),
                                                1700000000.0)])
    result = run_tshark(pcap, "-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "vw3.kind", "-e",
                        "vw3.request_frame", "-e", "vw3.warning", "-e", "_ws.col.Info", two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stdout[-2000:]
    mark = "" if two_pass else " [provisional]"
    infos = [REQUEST_INFO, ANSWER_INFO, REQUEST_INFO, REQUEST_INFO]
    assert result.stdout.splitlines() == [f"1,2,1,1|1|{WARNINGS[mode]}|" + "; ".join(f"{info}{mark}" for info in infos)]
    lua, _, _ = lua_items(pcap, two_pass=two_pass)
    # (the file, or standard input read once; a file of one record under -2 is read as a file: f32391e)
    run = subprocess.run([sys.executable, "-m", "dissector", str(pcap) if two_pass else "-", "--json"],
                         input=pcap.read_bytes(), capture_output=True, cwd=ROOT, timeout=300, check=True)
    decoded = [json.loads(line) for line in run.stdout.decode().splitlines()]
    assert compare(place_items(decoded, record_lengths(pcap)), lua) == []
