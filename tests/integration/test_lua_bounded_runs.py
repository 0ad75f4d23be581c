"""The plugin as vw3-decode on bytes with a good CRC that the line bounds (tests/differential/test_bounded_runs.py;
lua/src/rtu.lua bounded_run, take_bounded): pymodbus 3.16's answer to FC8 sub-function 15h (118 bytes, where the
table's FC8 layout takes 8) and '11 80 01' + CRC (an exception to function 0), a record each, were noise (one
pass: '(118 bytes continue)'), where tshark's mbrtu shows a frame. Exact fields (tshark -2), every field as
vw3-decode says it, and tshark's mbrtu on the same records."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import ensure_tool, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
ASK_PLUS, PLUS = rtu("01 08 0015 0003"), rtu("01 08 0015 0003" + "00" * 110)
EXCEPTION_0 = rtu("11 80 01")
POLL = rtu("01 03 0000 0002")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.function", "-e", "vw3.warning",
          "-e", "vw3.noise.reason"]
LONG = "frame length 118 disagrees with the spec's layout (8 bytes), its CRC good"
UNDEFINED = "diagnostic sub-function 21 is not defined by the spec"




def _mbrtu(pcap: Path) -> list[str]:
    """tshark's own Modbus RTU dissector on the records: the oracle that a record with a good CRC is a frame."""
    tshark = ensure_tool("tshark", "tshark")
    command = [tshark, "-n", "-r", str(pcap), "-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""',
               "-T", "fields", "-E", "separator=;", "-e", "mbrtu.unit_id", "-e", "modbus.func_code"]
    return subprocess.run(command, capture_output=True, text=True, timeout=300).stdout.splitlines()


def test_a_record_with_a_good_crc_is_a_frame(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "plus.pcap", [(ASK_PLUS, T0), (PLUS, T0 + 0.1), (EXCEPTION_0, T0 + 1.0)])
    assert tshark_fields(pcap, FIELDS) == [f"1;8;{UNDEFINED};", f"2;8;{LONG},{UNDEFINED};", "3;0;;"]
    assert _mbrtu(pcap) == ["1;8", "1;8", "17;0"]
    assert_same_as_vw3_decode(pcap)


def test_a_run_crosses_no_read_end(tmp_path: Path) -> None:
    char = 11 / 19200
    records = [(ASK_PLUS, T0), (PLUS[:50], T0 + 0.01), (PLUS[50:100], T0 + 0.01 + 50 * char),
               (PLUS[100:], T0 + 0.01 + 100 * char), (POLL, T0 + 1.0)]
    pcap = write_pcap(tmp_path / "bursts.pcap", records)
    assert_same_as_vw3_decode(pcap)
