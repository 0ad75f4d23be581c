"""lua/vw3_modbus.lua checks a Modbus/TCP request against the device as the serial plugin and vw3-decode do
(devices/checks.py check_request, lua/src/explain.lua): a function the device lacks, a quantity past its
limit (FC23: its read and write quantities). Before, the request was silent while the exception answering
it named the cause ('exception 03 from the VW3 A3 303 to Write Multiple Registers: quantity beyond the
card's limit'). The same PDUs over RTU under vw3-decode give the same warnings and notes (vw3-decode reads
serial captures only). Unit 12, profile atv71; tshark one pass and -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import PLUGIN
from lua_net import assert_device_checks, assert_same_over_rtu, write_modbus_tcp_pairs

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


@pytest.mark.parametrize("two_pass", [False, True])
def test_modbus_tcp_requests_checked_against_the_device(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_modbus_tcp_pairs(tmp_path / "mbtcp.pcap", PAIRS)
    assert_device_checks(pcap, PLUGIN.parent / "vw3_modbus.lua", WARNINGS, NOTES, two_pass)


def test_vw3_decode_says_the_same_of_these_pdus_over_rtu(tmp_path: Path) -> None:
    assert_same_over_rtu(tmp_path / "requests.rtu", PAIRS, WARNINGS, NOTES)
