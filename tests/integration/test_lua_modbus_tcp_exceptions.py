"""lua/vw3_modbus.lua explains an exception of Wireshark's own Modbus/TCP dissection as the RTU plugin
explains it (explain_exception): an exception 02 to a read on the ATV71 (p.38 of the VW3 A3 303 manual)
lists the registers of the read with the status it tells, and the device's meaning otherwise. Wireshark
gives an exception no modbus.request_frame: the file pairs it by connection and transaction id. Real
tshark, one pass and two."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from lua_harness import PLUGIN, lua_errors, run_tshark
from lua_net import NetWriter

pytestmark = pytest.mark.integration

NAMES = ("-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}")
ATV71 = ("-o", "vw3.profiles:atv71")
READ_8400 = bytes.fromhex("0320D00003")
ALL_PROTECTED = ("exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
                 "8400 non-existent, CHCF (8401) protected, COP (8402) protected")


def _mbap(transaction: int, pdu: bytes) -> bytes:
    return struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 0) + pdu


def _write(path: Path, packets: list[tuple[bool, int, int, bytes]]) -> Path:
    """packets: (to the server, client port, transaction id, PDU), 10 ms apart, to port 502."""
    writer = NetWriter(path)
    for index, (to_server, client_port, transaction, pdu) in enumerate(packets):
        writer.tcp(to_server, client_port, 502, _mbap(transaction, pdu), 1.0 + index * 0.01)
    writer.close()
    return path


def _rows(pcap: Path, *args: str, two_pass: bool = True) -> list[list[str]]:
    result = run_tshark(pcap, *NAMES, *args, "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                        "-e", "vw3.reg.address", "-e", "vw3.reg.code", "-e", "vw3.reg.status", "-e", "vw3.reg.text",
                        "-e", "vw3.note", two_pass=two_pass)
    assert result.returncode == 0, result.stderr
    assert not lua_errors(result.stdout + result.stderr), result.stderr
    return [line.split("|") for line in result.stdout.splitlines()]


def test_exception_02_to_a_read_lists_the_refused_registers(tmp_path: Path) -> None:
    # The seed's three reads of 8400..8402 (p.38): all readable but 8400, CHCF protected, then COP too:
    # exception 02. Frame 6 is told as the RTU plugin tells frame 10 of captures/p38_protection.pcap.
    pcap = _write(tmp_path / "p38.pcap", [
        (True, 40000, 1, READ_8400), (False, 40000, 1, bytes.fromhex("0306 8000 0003 0002")),
        (True, 40000, 2, READ_8400), (False, 40000, 2, bytes.fromhex("0306 8000 8000 0002")),
        (True, 40000, 3, READ_8400), (False, 40000, 3, bytes.fromhex("8302")),
    ])
    expected = [
        ["1", "", "", "", "", ""],
        ["2", "8400,8401,8402", ",CHCF,COP", "non-existent,ok,ok",
         "16#8000: non-existent (address not in the map),IO (I/O profile),Cd (command)", ""],
        ["3", "", "", "", "", ""],
        ["4", "8400,8401,8402", ",CHCF,COP", "non-existent,protected,ok",
         "16#8000: non-existent (address not in the map),16#8000: protected,Cd (command)",
         "CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"],
        ["5", "", "", "", "", ""],
        ["6", "8400,8401,8402", ",CHCF,COP", "non-existent,protected,protected",
         "no value: exception 02,no value: exception 02,no value: exception 02",
         f"{ALL_PROTECTED},COP (8402) became protected: read 2 in frame #4, exception 02 now"],
    ]
    assert _rows(pcap, *ATV71) == expected
    assert _rows(pcap, *ATV71, two_pass=False) == expected
    # The file's switch turns this off too.
    off = run_tshark(pcap, *NAMES, *ATV71, "-o", "vw3names.enabled:FALSE", "-T", "fields", "-e", "vw3.note",
                     "-e", "vw3.reg.status")
    assert off.stdout.split() == []


def test_exceptions_pair_by_connection_and_transaction(tmp_path: Path) -> None:
    # Two clients, requests outstanding at once, answers in another order: each exception lists the
    # registers of its own read (3102..3103: SFR and TFR, both mapped, so protected).
    pcap = _write(tmp_path / "two.pcap", [
        (True, 40001, 7, READ_8400),
        (True, 40002, 7, bytes.fromhex("030C1E0002")),
        (True, 40001, 8, bytes.fromhex("030C1E0002")),
        (False, 40001, 8, bytes.fromhex("8302")),
        (False, 40002, 7, bytes.fromhex("8302")),
        (False, 40001, 7, bytes.fromhex("8302")),
    ])
    rows = {row[0]: row[1:4] for row in _rows(pcap, *ATV71)}
    assert rows["4"] == ["3102,3103", "SFR,TFR", "protected,protected"]
    assert rows["5"] == ["3102,3103", "SFR,TFR", "protected,protected"]
    assert rows["6"] == ["8400,8401,8402", ",CHCF,COP", "non-existent,protected,protected"]


def test_exceptions_without_their_read_get_the_device_meaning(tmp_path: Path) -> None:
    # The read was not captured: the card's meaning of 02 alone, no registers; and the card's meaning of 02
    # to a write (no clause about reads), of 03 to a write past the card's 61 words.
    pcap = _write(tmp_path / "alone.pcap", [
        (False, 40000, 1, bytes.fromhex("8302")),
        (True, 40000, 2, bytes.fromhex("0620D10003")),
        (False, 40000, 2, bytes.fromhex("8602")),
        (True, 40000, 3, bytes.fromhex("1020D1003E7C") + bytes(124)),
        (False, 40000, 3, bytes.fromhex("9003")),
    ])
    rows = {row[0]: (row[1], row[5]) for row in _rows(pcap, *ATV71)}
    assert rows["1"] == ("", "exception 02 from the VW3 A3 303: address does not exist "
                             "(also: every parameter read is non-existent or protected)")
    assert rows["3"] == ("", "exception 02 from the VW3 A3 303: address does not exist")
    assert rows["5"] == ("", "exception 03 from the VW3 A3 303 to Write Multiple Registers: "
                             "quantity beyond the card's limit")
