"""Writes confirmed under Wireshark's Modbus/TCP before profile `auto` chose the unit's device are remembered
by the device it chooses (lua/src/annotator.lua, annotate_again, replays the held frames of vw3_modbus.lua
as its name_adu did: an FC6 echo's value, as the RTU plugin's annotate_with and vw3-decode's annotator), so a
later 16#8000 is told against the value written, as an RTU capture tells it (the case `writes` of the
provisional replay tests). Before, the replay named the registers only: the chosen ATV71 had no memory of the
write and said nothing. tshark one pass and -2 (the names are made once, in capture order)."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from lua_harness import PLUGIN, lua_errors, run_tshark
from lua_net import NetWriter

pytestmark = pytest.mark.integration

# unit 12: FC6 8401 (CHCF) = 3 and its echo; a read of 8400..8413, 16#8000 but FR1 (8413) = 1, that makes
# profile auto choose the ATV71 (8400 in no map: its 16#8000 is evidence)
PAIRS = [("0620D10003", "0620D10003"), ("0320D0000E", "031C" + "8000" * 13 + "0001")]
EXPECTED = [
    "|", "|", "|",
    ",CHCF,COP,,,,,,,,,,,FR1|CHCF (8401) became protected: written 3 in frame #2, 16#8000 now",
]


def codes_and_notes(tmp_path: Path, pairs: list[tuple[str, str]], two_pass: bool) -> list[str]:
    """The pairs as Modbus/TCP transactions to unit 12, read by vw3_modbus.lua: each frame's codes | notes."""
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, pdu in ((True, bytes.fromhex(request)), (False, bytes.fromhex(response))):
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 12) + pdu, time)
            time += 0.01
    writer.close()
    done = run_tshark(tmp_path / "mbtcp.pcap", "-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}", "-T", "fields",
                      "-E", "separator=|", "-e", "vw3.reg.code", "-e", "vw3.note", two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    return done.stdout.splitlines()


@pytest.mark.parametrize("two_pass", [False, True])
def test_a_write_before_the_choice_is_remembered(tmp_path: Path, two_pass: bool) -> None:
    assert codes_and_notes(tmp_path, PAIRS, two_pass) == EXPECTED


# The confirmed writes are kept with the frame and an FC16 answer is held as any frame before the choice:
# FC6 8401 (CHCF) = 3, then FC16 8402 (COP) = 2 before the choice (an FC16 answer carries no registers).
PAIRS_MULTIPLE = [("0620D10003", "0620D10003"), ("1020D20001020002", "1020D20001"),
                  ("0320D0000E", "031C" + "8000" * 13 + "0001")]
EXPECTED_MULTIPLE = [
    "|", "|", "|", "|", "|",
    ",CHCF,COP,,,,,,,,,,,FR1|CHCF (8401) became protected: written 3 in frame #2, 16#8000 now,"
    "COP (8402) became protected: written 2 in frame #4, 16#8000 now",
]


@pytest.mark.parametrize("two_pass", [False, True])
def test_writes_an_answer_confirms_before_the_choice_are_remembered(tmp_path: Path, two_pass: bool) -> None:
    assert codes_and_notes(tmp_path, PAIRS_MULTIPLE, two_pass) == EXPECTED_MULTIPLE
