"""lua/vw3_modbus.lua checks a Modbus/TCP request against the device as the serial plugin and vw3-decode do
(devices/checks.py check_request, lua/src/explain.lua): a function the device lacks, a quantity past its
limit (FC23: its read and write quantities). Before, the request was silent while the exception answering
it named the cause ('exception 03 from the VW3 A3 303 to Write Multiple Registers: quantity beyond the
card's limit'). The same PDUs over RTU under vw3-decode give the same warnings and notes (vw3-decode reads
serial captures only). Unit 12, profile atv71; tshark one pass and -2."""
from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from helpers import run_cli, write_rtu
from lua_harness import PLUGIN, lua_errors, run_tshark
from lua_net import NetWriter

pytestmark = pytest.mark.integration

# (request, response) PDUs: FC16 of 62 words at CHCF (8401: the card's limit 61) refused 03; FC3 of 64 words
# (limit 63) refused 03; FC23 reading 21 (limit 20), writing 1, refused 03; FC12 (the card has none) refused
# 01; FC3 of 3 words answered (within the limit: silent).
PAIRS = [("1020D1003E7C" + "0001" * 62, "9003"), ("0320D10040", "8303"), ("1720D1001520D100010200 03", "9703"),
         ("0C", "8C01"), ("0320D10003", "0306000300040005")]
WARNINGS = ["quantity 62 is beyond the VW3 A3 303's limit of 61 words for Write Multiple Registers",
            "quantity 64 is beyond the VW3 A3 303's limit of 63 words for Read Holding Registers",
            "read quantity 21 is beyond the VW3 A3 303's limit of 20 words for Read/Write Multiple Registers",
            "Get Comm Event Log (12) is not supported by the VW3 A3 303", ""]
LIMIT = "exception 03 from the VW3 A3 303 to {}: quantity beyond the card's limit"
NOTES = [LIMIT.format("Write Multiple Registers"), LIMIT.format("Read Holding Registers"),
         LIMIT.format("Read/Write Multiple Registers"), "exception 01 from the VW3 A3 303: function not recognized",
         ""]


def capture(path: Path) -> Path:
    writer = NetWriter(path)
    time = 1.0
    for transaction, (request, response) in enumerate(PAIRS, start=1):
        for to_server, pdu in ((True, bytes.fromhex(request.replace(" ", ""))), (False, bytes.fromhex(response))):
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 12) + pdu, time)
            time += 0.01
    writer.close()
    return path


@pytest.mark.parametrize("two_pass", [False, True])
def test_modbus_tcp_requests_checked_against_the_device(tmp_path: Path, two_pass: bool) -> None:
    done = run_tshark(capture(tmp_path / "mbtcp.pcap"), "-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}",
                      "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                      "-e", "vw3.warning", "-e", "vw3.note", two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    lines = done.stdout.splitlines()
    assert lines[0::2] == [f"{2 * index + 1}|{warning}|" for index, warning in enumerate(WARNINGS)]
    assert lines[1::2] == [f"{2 * index + 2}||{note}" for index, note in enumerate(NOTES)]


def test_vw3_decode_says_the_same_of_these_pdus_over_rtu(tmp_path: Path) -> None:
    path = write_rtu(tmp_path / "requests.rtu", [f"0C{pdu}".replace(" ", "") for pair in PAIRS for pdu in pair])
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", str(path)])[1].splitlines()]
    assert [",".join(frame["warnings"]) for frame in frames[0::2]] == WARNINGS
    assert [",".join(frame["notes"]) for frame in frames[1::2]] == NOTES
