"""A real line's read of 56 registers and its 117-byte answer, as a sniffer that cuts records at gaps wrote
it (j123b567/SerialPCAP issue #5, "Packet size limited during capture: Modbus RTU truncated", 2018-10-04:
the poll `01 03 00 F3 00 38 B4 2B` and the answer `01 03 70 ...  50 E5` as its reporter quoted them, CRC
good, recorded on an RS-485 network; the sniffer split the answer into rows that tshark showed as 'Unable
to classify as query or response'). Here as the reads of an adapter that hands 32 bytes a read, each late:
vw3-decode (engine and VW3_PURE_PYTHON=1) and the plugin frame the answer whole across its records, pair
it with its poll and read its 56 registers; tshark's mbrtu, which takes a record for a frame, shows its
first record as a cut response and the next ones as unknown function 0, as the issue reports."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import write_pcap

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
POLL = bytes.fromhex("01 03 00 F3 00 38 B4 2B")
ANSWER = bytes.fromhex(
    "01 03 70 00 00 11 E1 00 00 00 00 00 00 EA 89 00 03 00 00 00 00 E6 03 00 03 00 00 00 00 E2 6D 00 "
    "07 00 00 00 00 F7 62 00 03 00 00 00 00 F0 44 00 03 00 00 00 00 EB 3F 00 03 00 00 00 00 D2 E5 00 "
    "0B 00 00 00 00 FB AA FF FF FF FF FF FF FA 46 FF FF FF FF FF FF FA C4 FF FF FF FF FF FF F0 B4 FF "
    "FF FF FF FF FF A5 81 FF FF FF FF FF FF A7 F6 FF FF FF FF 50 E5")
REGISTERS = [0, 4577, 0, 0, 0, 60041, 3, 0, 0, 58883, 3, 0, 0, 57965, 7, 0, 0, 63330, 3, 0, 0, 61508, 3,
             0, 0, 60223, 3, 0, 0, 53989, 11, 0, 0, 64426, 65535, 65535, 65535, 64070, 65535, 65535, 65535,
             64196, 65535, 65535, 65535, 61620, 65535, 65535, 65535, 42369, 65535, 65535, 65535, 42998, 65535,
             65535]
CHARACTER = 11 / 9600
MBRTU = ["-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""', "-o", "mbrtu.crc_verification:TRUE"]


def capture(path: Path) -> Path:
    """Three polls 1 s apart, each answer after 20 ms in reads of 32 bytes, each 6 ms late (silences of more
    than t3.5 inside the answer)."""
    records, start = [], 1_538_611_200.0
    for _ in range(3):
        records.append((POLL, start))
        for at in range(0, len(ANSWER), 32):
            piece = ANSWER[at : at + 32]
            records.append((piece, start + 0.02 + (at + len(piece)) * CHARACTER + 0.006))
        start += 1
    return write_pcap(path, records)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_the_answer_is_framed_whole(pure: bool, tmp_path: Path) -> None:
    assert len(ANSWER) == 117 and len(REGISTERS) == 56
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    pcap = capture(tmp_path / "split.pcap")
    command = [sys.executable, "-m", "dissector", "--json", "-n", "--baud", "9600", str(pcap)]
    done = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    items = [json.loads(line) for line in done.stdout.splitlines()]
    assert [(item["kind"], item["raw"], item["crc_ok"]) for item in items] == [
        ("request", POLL.hex(), True), ("response", ANSWER.hex(), True)] * 3
    assert all(items[k + 1]["request_frame"] == items[k]["frame"] for k in range(0, 6, 2))
    assert [register["value"] for register in items[1]["registers"]] == REGISTERS
    assert (items[1]["start"], items[1]["registers"][-1]["address"]) == (243, 298)


def test_the_plugin_frames_it_whole_where_mbrtu_cannot(tmp_path: Path) -> None:
    pcap = capture(tmp_path / "split.pcap")
    fields = ["-T", "fields", "-E", "separator=;", "-e", "frame.len", "-e", "vw3.kind"]
    assert tshark_fields(pcap, fields) == ["8;1", "32;", "32;", "32;", "21;2"] * 3
    assert_same_as_vw3_decode(pcap)
    command = ["tshark", *MBRTU, "-r", str(pcap), "-T", "fields", "-E", "separator=;", "-e", "mbrtu.unit_id",
               "-e", "modbus.func_code"]
    shown = subprocess.run(command, capture_output=True, text=True, timeout=120)
    # (the first record: a cut response, its unit only; the next ones: function 0, as the issue shows)
    assert shown.stdout.splitlines()[:4] == ["1;3", "1;", "7;0", "11;0"]
