"""lua/vw3_modbus.lua warns a Modbus/TCP write of a read-only map row (access R) on its request, as the
serial plugin and vw3-decode warn it (devices/access.py check_writes: `ETA (3201) is read-only
(access R)`): FC6, FC16, FC22's address, FC23's write window; the exception 02 refusing it already named the
parameters (its note), and its meaning is the refusal's (test_read_only_meaning). Before, the request was
silent. The same PDUs over RTU under vw3-decode give the same warnings and notes (vw3-decode reads serial
captures only). Unit 12, profile atv71; tshark one pass and -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import PLUGIN
from lua_net import assert_device_checks, assert_same_over_rtu, write_modbus_tcp_pairs

pytestmark = pytest.mark.integration

# (request, response) PDUs: FC6 of ETA (3201, R) refused 02; FC16 of ETA, RFR (3202, R) refused 02; FC22
# of ETA refused 02; FC23 reading RFR, writing ETA, refused 02; FC6 of CHCF (8401, RW) echoed; FC16 of
# CHCF, COP (8402, RW) answered.
PAIRS = [("060C810007", "8602"), ("100C810002040001000A", "9002"), ("160C8100FF0000", "9602"),
         ("170C8200010C8100010200 03".replace(" ", ""), "9702"), ("0620D10003", "0620D10003"),
         ("1020D1000204000300 05".replace(" ", ""), "1020D10002")]
ETA, RFR = "ETA (3201) is read-only (access R)", "RFR (3202) is read-only (access R)"
# (the ATV71 has no FC22: checked against the device too, test_lua_modbus_tcp_request_checks)
WARNINGS = [ETA, f"{ETA},{RFR}", f"Mask Write Register (22) is not supported by the VW3 A3 303,{ETA}", ETA, "", ""]
REFUSED = "exception 02 from the VW3 A3 303: {} read-only (access R), not written"
NOTES = [REFUSED.format("ETA (3201)"), REFUSED.format("ETA (3201), RFR (3202)"), REFUSED.format("ETA (3201)"),
         REFUSED.format("ETA (3201)"), "", ""]


@pytest.mark.parametrize("two_pass", [False, True])
def test_modbus_tcp_read_only_writes_warned(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_modbus_tcp_pairs(tmp_path / "mbtcp.pcap", PAIRS)
    assert_device_checks(pcap, PLUGIN.parent / "vw3_modbus.lua", WARNINGS, NOTES, two_pass)


def test_vw3_decode_says_the_same_of_these_pdus_over_rtu(tmp_path: Path) -> None:
    assert_same_over_rtu(tmp_path / "writes.rtu", PAIRS, WARNINGS, NOTES)
