"""A Mask Write (FC22) its echo confirms under Wireshark's Modbus/TCP changes the parameter memory as the
RTU plugin's does (lua/vw3_modbus.lua: the echo's modbus.reference_num, and_mask and or_mask;
lua/src/story.lua remember_mask, memory.remember_mask): the register holds (current AND and_mask) OR
(or_mask AND NOT and_mask) where the current value is known (or and_mask is 0), the parameter is
forgotten otherwise. The PDUs of tests/integration/test_mask_write_memory.py's serial capture (profile
atv71) to unit 12: the same register texts and notes as the RTU plugin's (its PLUGIN_LINES). Before,
vw3_modbus.lua ignored FC22: 'COP (8402) became protected: read 18 in frame #2', CMD not plain once
CHCF was masked to 1. Under profile auto an FC22 echo is evidence as on a serial line (answered, a
function the ATV71 lacks): the read that chose the ATV71 before no longer does, as vw3-decode reads the
same PDUs over RTU. vw3-decode reads serial captures only (no Modbus/TCP). tshark one pass and -2."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import PLUGIN, lua_errors, run_tshark
from lua_net import NetWriter
from test_mask_write_memory import FRAMES, PLUGIN_LINES

pytestmark = pytest.mark.integration

# The serial test's frames as (request, response) PDUs, unit 12 dropped: each frame is "0C <PDU>".
PDUS = [frame[3:].replace(" ", "") for frame in FRAMES]
PAIRS = list(zip(PDUS[0::2], PDUS[1::2]))
# 16#8000 but FR1 (8413) after a write: profile auto chose the ATV71 (test_lua_modbus_tcp_auto_writes)
# before the mask was read; the mask answered, no profile whose device supports it fits.
CHOOSE_AFTER_A_MASK = [("0320D20001", "03020012"), ("1620D200F20025", "1620D200F20025"),
                       ("0320D0000E", "031C" + "8000" * 13 + "0001")]


def responses(tmp_path: Path, pairs: list[tuple[str, str]], two_pass: bool, *options: str) -> list[str]:
    """The pairs as Modbus/TCP transactions to unit 12 read by vw3_modbus.lua: each response's frame number |
    register texts | notes, as the serial test's PLUGIN_LINES."""
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, pdu in ((True, bytes.fromhex(request)), (False, bytes.fromhex(response))):
            mbap = struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 12)
            writer.tcp(to_server, 40000, 502, mbap + pdu, time)
            time += 0.01
    writer.close()
    fields = ("-e", "frame.number", "-e", "vw3.reg.text", "-e", "vw3.note")
    script = f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}"
    done = run_tshark(tmp_path / "mbtcp.pcap", "-X", script, *options,
                      "-T", "fields", "-E", "separator=|", *fields, two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    lines = done.stdout.splitlines()
    # (the requests: nothing named)
    assert [line.split("|", 1)[1] for line in lines[0::2]] == ["|"] * len(pairs)
    return lines[1::2]


# (but the echoes' own register, frames 4, 6 and 12: the serial plugin lists an FC22 frame's register as
# vw3-decode --json does; vw3_modbus.lua names Wireshark's registers, and its Modbus tree shows the masks)
TCP_LINES = [line if line.split("|")[0] not in ("4", "6", "12") else line.split("|")[0] + "||"
             for line in PLUGIN_LINES]


@pytest.mark.parametrize("two_pass", [False, True])
def test_a_confirmed_mask_write_changes_the_memory(tmp_path: Path, two_pass: bool) -> None:
    assert responses(tmp_path, PAIRS, two_pass, "-o", "vw3.profiles:atv71") == TCP_LINES


@pytest.mark.parametrize("two_pass", [False, True])
def test_a_mask_write_is_evidence_for_profile_auto(tmp_path: Path, two_pass: bool) -> None:
    named = responses(tmp_path, CHOOSE_AFTER_A_MASK, two_pass)
    assert named == ["2||", "4||", "6|" + "," * 13 + "|"]  # (no device: its 14 registers have no text)
    capture = tmp_path / "mask.bin"
    capture.write_bytes(b"".join(rtu(f"0C{pdu}") for pair in CHOOSE_AFTER_A_MASK for pdu in pair))
    status, out, err = run_cli([str(capture), "--profile", "auto"])
    assert status == 0, err
    assert "8400=32768 8401=32768" in out  # (no device: spec semantics only)
