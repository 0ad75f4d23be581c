"""A Mask Write (FC22) its echo confirms under Wireshark's Modbus/TCP changes the parameter memory as the
RTU plugin's does (lua/vw3_modbus.lua: the echo's modbus.reference_num, and_mask and or_mask;
lua/src/story.lua remember_mask, memory.remember_mask): the register holds (current AND and_mask) OR
(or_mask AND NOT and_mask) where the current value is known (or and_mask is 0), the parameter is
forgotten otherwise. The PDUs of tests/integration/test_mask_write_memory.py's serial capture (profile
atv71) to unit 12: the same register texts and notes as the RTU plugin's (its PLUGIN_LINES). Before,
vw3_modbus.lua ignored FC22: 'COP (8402) became protected: read 18 in frame #2', CMD not plain once
CHCF was masked to 1. Under profile auto an FC22 echo is evidence as on a serial line (answered, a
function the ATV71 lacks): the read that chose the ATV71 before no longer does, as vw3-decode reads the
same PDUs over RTU. vw3-decode reads serial captures only (no Modbus/TCP). tshark one pass and -2.
An FC22 request and echo list their register (address, masks as text, the value where and_mask is 0), as the
RTU plugin's tree does (tree.lua mask_register); before, vw3_modbus.lua listed none (Wireshark lists none)."""
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
    # (the requests: nothing named but an FC22's register, as its echo's: the serial plugin's tree.lua add_pdu)
    assert [line.split("|", 1)[1] for line in lines[0::2]] == [
        answer.split("|", 1)[1] if request.startswith("16") else "|"
        for (request, _), answer in zip(pairs, lines[1::2])]
    return lines[1::2]


@pytest.mark.parametrize("two_pass", [False, True])
def test_a_confirmed_mask_write_changes_the_memory(tmp_path: Path, two_pass: bool) -> None:
    """The echoes' own register too (frames 4, 6 and 12), as the serial plugin lists an FC22 frame's register
    and vw3-decode --json does (before: vw3_modbus.lua showed none, Wireshark lists no register for FC22)."""
    assert responses(tmp_path, PAIRS, two_pass, "-o", "vw3.profiles:atv71") == PLUGIN_LINES


# The FC22 register's fields under both address styles, as the serial plugin's for the same PDUs (its PLC label
# from the device: 48403), on the or mask's bytes.
REGISTER_FIELDS = ["vw3.reg.address", "vw3.reg.label", "vw3.reg.value", "vw3.reg.code", "vw3.reg.text"]
MASK_REGISTERS = [  # (address, its PLC label, the rest)
    ("8402", "48403", "|||AND 0x00F2 OR 0x0025: the result depends on the value before"),
    ("8401", "48402", "|1||AND 0x0000 OR 0x0001"),
]


@pytest.mark.parametrize("style", ["profile", "plc"])
def test_the_mask_register_has_the_serial_plugins_fields(tmp_path: Path, style: str) -> None:
    writer = NetWriter(tmp_path / "mask.pcap")
    for transaction, (request, response) in enumerate(PAIRS[1:3], start=1):
        for to_server, pdu in ((True, bytes.fromhex(request)), (False, bytes.fromhex(response))):
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 12) + pdu,
                       transaction + (0 if to_server else 0.01))
    writer.close()
    script = f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}"
    fields = [arg for name in REGISTER_FIELDS for arg in ("-e", name)]
    done = run_tshark(tmp_path / "mask.pcap", "-X", script, "-o", "vw3.profiles:atv71", "-o",
                      f"vw3.address_style:{style}", "-T", "fields", "-E", "separator=|", *fields)
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr), done.stderr
    expected = [f"{address}|{label if style == 'plc' else ''}{rest}" for address, label, rest in MASK_REGISTERS]
    assert done.stdout.splitlines() == [expected[0], expected[0], expected[1], expected[1]]
    # (on the or mask's two bytes: 54 of headers, 7 of MBAP, then code, address and and mask)
    tree = run_tshark(tmp_path / "mask.pcap", "-X", script, "-o", "vw3.profiles:atv71", "-T", "pdml").stdout
    assert tree.count('<field name="vw3.reg" showname="Register 8402: AND 0x00F2 OR 0x0025: the result depends on '
                      'the value before" size="2" pos="66"') == 2


@pytest.mark.parametrize("two_pass", [False, True])
def test_a_mask_write_is_evidence_for_profile_auto(tmp_path: Path, two_pass: bool) -> None:
    named = responses(tmp_path, CHOOSE_AFTER_A_MASK, two_pass)
    # (no device: its 14 registers have no text; the echo's register its masks, as the serial plugin's)
    assert named == ["2||", "4|AND 0x00F2 OR 0x0025: the result depends on the value before|", "6|" + "," * 13 + "|"]
    capture = tmp_path / "mask.bin"
    capture.write_bytes(b"".join(rtu(f"0C{pdu}") for pair in CHOOSE_AFTER_A_MASK for pdu in pair))
    status, out, err = run_cli([str(capture), "--profile", "auto"])
    assert status == 0, err
    assert "8400=32768 8401=32768" in out  # (no device: spec semantics only)
