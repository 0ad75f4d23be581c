"""Modbus/TCP (lua/vw3_modbus.lua, under Wireshark's own Modbus/TCP dissection): an FC16 request whose byte
count carries more values than its quantity (quantity 1, byte count 4: 8401 = 3, then 00 02) writes one
register. Wireshark 4.0 lists every value of the byte count (Register 8402 too); vw3_modbus.lua named 8402
COP and remembered it as written once the answer came, so a later 16#8000 there said `COP (8402) became
protected: written 2 in frame #2`, where the RTU plugin and vw3-decode write no value past the quantity
(data/modbus.toml [lift] values' `most`, tests/integration/test_write_past_quantity.py). tshark one pass
and -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from test_lua_modbus_tcp_auto_writes import codes_and_notes

pytestmark = pytest.mark.integration

# unit 12: FC6 8401 (CHCF) = 3 and its echo; FC16 8401 (quantity 1) = 3 with 00 02 past the quantity, its
# answer; then a read of 8400..8413, 16#8000 but FR1 (8413) = 1, that makes profile auto choose the ATV71.
# Before: frame 3 held two registers (`,|`) and the read said `8401..8402 became protected (2): written in
# frame #4, 16#8000 now`.
PAIRS = [("0620D10003", "0620D10003"), ("1020D1000104" "0003" "0002", "1020D10001"),
         ("0320D0000E", "031C" + "8000" * 13 + "0001")]
EXPECTED = [
    "|", "|", "|", "|", "|",
    ",CHCF,COP,,,,,,,,,,,FR1|CHCF (8401) became protected: written 3 in frame #4, 16#8000 now",
]


@pytest.mark.parametrize("two_pass", [False, True])
def test_no_value_past_the_quantity_is_written(tmp_path: Path, two_pass: bool) -> None:
    assert codes_and_notes(tmp_path, PAIRS, two_pass) == EXPECTED
