"""lua/vw3_modbus.lua names each Modbus/TCP ADU with its own unit and transaction: a TCP segment carrying
two ADUs (and a segment completing a reassembled ADU besides one of its own) shows one "VW3 register
names" tree per ADU, each with its unit's profile. FC6 and FC23, which Wireshark 4.0 shows as a reference
and modbus.data (no modbus.regnum16), are named as vw3-decode names the same PDUs, and confirmed writes
(FC6's echo, FC16's and FC23's answer) feed the parameter story. Real tshark, one pass and two."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from lua_harness import PLUGIN, lua_errors, run_tshark
from lua_net import NetWriter

pytestmark = pytest.mark.integration

NAMES = ("-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}")
ATV71 = ("-o", "vw3.profiles:atv71")


def _mbap(transaction: int, pdu: str, unit: int = 0) -> bytes:
    data = bytes.fromhex(pdu)
    return struct.pack("!HHHB", transaction, 0, len(data) + 1, unit) + data


def _pairs(path: Path, pairs: list[tuple[str, str]]) -> Path:
    """Request and response PDUs, one ADU a segment, transactions 1, 2, ... of unit 0, 10 ms apart."""
    writer = NetWriter(path)
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, pdu in ((True, request), (False, response)):
            writer.tcp(to_server, 40000, 502, _mbap(transaction, pdu), time)
            time += 0.01
    writer.close()
    return path


def _fields(pcap: Path, *args: str, two_pass: bool = True) -> list[str]:
    result = run_tshark(pcap, *NAMES, *args, "-T", "fields", "-E", "separator=|", two_pass=two_pass)
    assert result.returncode == 0, result.stderr
    assert not lua_errors(result.stdout + result.stderr), result.stdout + result.stderr
    return result.stdout.splitlines()


def _trees(pcap: Path, *args: str, two_pass: bool = True) -> list[str]:
    """The names trees of -V: each tree's title and its registers' lines."""
    result = run_tshark(pcap, *NAMES, *args, "-V", "-O", "vw3names", two_pass=two_pass)
    assert result.returncode == 0, result.stderr
    assert not lua_errors(result.stdout + result.stderr), result.stdout + result.stderr
    return [line for line in result.stdout.splitlines()
            if line.startswith("VW3 register names") or line.startswith("    Register ")]


def test_two_adus_in_one_segment_each_with_its_unit(tmp_path: Path) -> None:
    # Units 0 (ATV71) and 5 (generic) asked the same read in one segment, answered in one segment.
    writer = NetWriter(tmp_path / "two.pcap")
    writer.tcp(True, 40000, 502, _mbap(1, "030C1E0002", 0) + _mbap(2, "030C1E0002", 5), 1.0)
    writer.tcp(False, 40000, 502, _mbap(1, "030400280258", 0) + _mbap(2, "030400110022", 5), 1.01)
    writer.close()
    pcap = tmp_path / "two.pcap"
    for two_pass in (True, False):
        rows = _fields(pcap, "-o", "vw3.profiles:0=atv71,5=generic", "-e", "mbtcp.unit_id", "-e", "vw3.reg.address",
                       "-e", "vw3.reg.code", "-e", "vw3.reg.text", two_pass=two_pass)
        # (unit 5 is generic: its registers have no code and no text)
        assert rows == ["0,5|||", "0,5|3102,3103,3102,3103|SFR,TFR,,|4.0 kHz,60.0 Hz,,"], two_pass
        assert _trees(pcap, "-o", "vw3.profiles:0=atv71,5=atv71", two_pass=two_pass) == [
            "VW3 register names (Altivar 71 (VW3 A3 303 Modbus card), unit 0)",
            "    Register 3102 SFR = 40: 4.0 kHz [ok]",
            "    Register 3103 TFR = 600: 60.0 Hz [ok]",
            "VW3 register names (Altivar 71 (VW3 A3 303 Modbus card), unit 5)",
            "    Register 3102 SFR = 17: 1.7 kHz [ok]",
            "    Register 3103 TFR = 34: 3.4 Hz [ok]",
        ], two_pass


def test_every_transaction_of_a_segment_is_paired(tmp_path: Path) -> None:
    # Two requests in one segment, each answered in a segment of its own: an FC23 answer (registers from
    # its request's read window) and an exception 02 to a read (its registers from its request; CHCF was
    # written 3 by the FC23 its answer confirmed).
    writer = NetWriter(tmp_path / "paired.pcap")
    writer.tcp(True, 40000, 502, _mbap(1, "0320D00003") + _mbap(2, "170C1E000220D10001020003"), 1.0)
    writer.tcp(False, 40000, 502, _mbap(2, "170400280258"), 1.01)
    writer.tcp(False, 40000, 502, _mbap(1, "8302"), 1.02)
    writer.close()
    for two_pass in (True, False):
        rows = _fields(tmp_path / "paired.pcap", *ATV71, "-e", "frame.number", "-e", "vw3.reg.address", "-e", "vw3.reg.code",
                       "-e", "vw3.reg.status", "-e", "vw3.note", two_pass=two_pass)
        assert rows == [
            "1|8401|CHCF||",
            "2|3102,3103|SFR,TFR|ok,ok|",
            "3|8400,8401,8402|,CHCF,COP|non-existent,protected,protected|exception 02 from the VW3 A3 303: every "
            "parameter of this read is non-existent or protected: 8400 non-existent, CHCF (8401) protected, "
            "COP (8402) protected,CHCF (8401) became protected: written 3 in frame #2, exception 02 now",
        ], two_pass


def test_a_reassembled_adu_and_one_of_the_segment_as_long_as_the_frame(tmp_path: Path) -> None:
    # The answer to unit 0 (69 bytes) ends in the segment that carries unit 5's whole answer; the frame is
    # 69 bytes too, so the data sources' lengths alone do not tell the ADUs apart.
    writer = NetWriter(tmp_path / "split.pcap")
    writer.tcp(True, 40000, 502, _mbap(1, "0320D0001E", 0) + _mbap(2, "030C1E0002", 5), 1.0)
    answers = _mbap(1, "033C" + "800000030002" + "00" * 54, 0) + _mbap(2, "030400110022", 5)
    writer.tcp(False, 40000, 502, answers[:67], 1.01)
    writer.tcp(False, 40000, 502, answers[67:], 1.02)
    writer.close()
    pcap = tmp_path / "split.pcap"
    assert _fields(pcap, "-e", "frame.number", "-e", "frame.len") == ["1|78", "2|121", "3|69"]
    for two_pass in (True, False):
        trees = _trees(pcap, "-o", "vw3.profiles:0=atv71,5=atv71", two_pass=two_pass)
        assert trees[0] == "VW3 register names (Altivar 71 (VW3 A3 303 Modbus card), unit 0)"
        assert trees[1:4] == ["    Register 8400 = 32768: 16#8000: non-existent (address not in the map) [non-existent]",
                              "    Register 8401 CHCF = 3: IO (I/O profile) [ok]",
                              "    Register 8402 COP = 2: Cd (command) [ok]"], two_pass
        assert len(trees) == 1 + 30 + 3, two_pass
        assert trees[-3:] == ["VW3 register names (Altivar 71 (VW3 A3 303 Modbus card), unit 5)",
                              "    Register 3102 SFR = 17: 1.7 kHz [ok]",
                              "    Register 3103 TFR = 34: 3.4 Hz [ok]"], two_pass


def test_fc6_and_fc23_are_named(tmp_path: Path) -> None:
    # Wireshark 4.0: FC6 is modbus.reference_num and modbus.data, FC23 read and write reference numbers
    # and modbus.data; vw3-decode names FC6 8401 = 3 CHCF = IO (I/O profile) in the request and its echo.
    pcap = _pairs(tmp_path / "codes.pcap", [
        ("030C1E0004", "03080028025801F40000"), ("0620D10003", "0620D10003"),
        ("1020D100020400030002", "1020D10002"), ("040C1E0002", "040400280258"),
        ("170C1E000220D10001020003", "170400280258"),
    ])
    for two_pass in (True, False):
        rows = _fields(pcap, *ATV71, "-e", "frame.number", "-e", "modbus.func_code", "-e", "vw3.reg.address",
                       "-e", "vw3.reg.code", "-e", "vw3.reg.text", two_pass=two_pass)
        assert rows == [
            "1|3|||", "2|3|3102,3103,3104,3105|SFR,TFR,HSP,LSP|4.0 kHz,60.0 Hz,50.0 Hz,0.0 Hz",
            "3|6|8401|CHCF|IO (I/O profile)", "4|6|8401|CHCF|IO (I/O profile)",
            "5|16|8401,8402|CHCF,COP|IO (I/O profile),Cd (command)", "6|16|||",
            "7|4|||", "8|4|3102,3103|SFR,TFR|4.0 kHz,60.0 Hz",
            "9|23|8401|CHCF|IO (I/O profile)", "10|23|3102,3103|SFR,TFR|4.0 kHz,60.0 Hz",
        ], two_pass
    # The value's own bytes: FC6's data, the FC23 answer's two registers in its data.
    result = run_tshark(pcap, *NAMES, *ATV71, "-T", "pdml", "-Y", "frame.number == 4 or frame.number == 10")
    values = [line.strip() for line in result.stdout.splitlines() if 'name="vw3.reg.value"' in line]
    assert values == ['<field name="vw3.reg.value" showname="Value: 3 (0x0003)" size="2" pos="64" show="3" value="0003"/>',
                      '<field name="vw3.reg.value" showname="Value: 40 (0x0028)" size="2" pos="63" show="40" value="0028"/>',
                      '<field name="vw3.reg.value" showname="Value: 600 (0x0258)" size="2" pos="65" show="600" '
                      'value="0258"/>']


@pytest.mark.parametrize("write", [("0620D10003", "0620D10003"), ("1020D100020400030002", "1020D10002"),
                                   ("170C1E000220D10001020003", "170400280258")], ids=["fc6", "fc16", "fc23"])
def test_confirmed_writes_feed_the_parameter_story(tmp_path: Path, write: tuple[str, str]) -> None:
    # CHCF written 3 (confirmed in frame 2), then read as 16#8000: vw3-decode's note for the same PDUs over RTU.
    pcap = _pairs(tmp_path / "story.pcap", [write, ("0320D00003", "0306800080000002")])
    for two_pass in (True, False):
        rows = _fields(pcap, *ATV71, "-e", "frame.number", "-e", "vw3.reg.status", "-e", "vw3.note",
                       two_pass=two_pass)
        assert rows[3] == "4|non-existent,protected,ok|CHCF (8401) became protected: written 3 in frame #2, 16#8000 now"
