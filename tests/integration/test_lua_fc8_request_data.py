"""The plugin says what an FC8 request's data word means, and warns about one the spec does not allow, as
vw3-decode does (tests/unit/test_fc8_request_data.py, data/modbus.toml [diagnostic_data]). Before: nothing.
Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.subfunction", "-e", "vw3.warning",
          "-e", "vw3.note"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


def refused(data: str, subfunction: str, allowed: str) -> str:
    return f"diagnostic data {data} is not what sub-function {subfunction} takes ({allowed}): a server answers exception 03"


@pytest.mark.parametrize("two_pass", [True, False])
def test_request_data(tmp_path: Path, two_pass: bool) -> None:
    frames = [rtu("01 08 0001 FF00"), rtu("01 08 0001 FF00"), rtu("01 08 0001 0000"), rtu("01 08 0001 0000"),
              rtu("01 08 0003 3B00"), rtu("01 08 0003 3B00"), rtu("01 08 0003 0A00"), rtu("01 08 0003 0A00"),
              rtu("01 08 0003 0100"), rtu("01 08 0003 0100"), rtu("01 08 000B 0001"), rtu("01 88 03"),
              rtu("01 08 000B 0000"), rtu("01 08 000B 0007"), rtu("01 08 0003 3B01"), rtu("01 88 03"),
              rtu("01 08 0001 1234"), rtu("01 88 03"), rtu("01 08 0000 1234"), rtu("01 08 0000 1234"),
              rtu("01 08 0014 FFFF"), rtu("01 88 03")]
    pcap = write_pcap(tmp_path / "fc8.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;1;;clear the communications event log", "2;1;;",
        "1;1;;", "2;1;;",
        "1;3;;new ASCII input delimiter: ';' (3Bh)", "2;3;;",
        "1;3;;new ASCII input delimiter: LF (0Ah)", "2;3;;",
        "1;3;;new ASCII input delimiter: 01h", "2;3;;",
        f"1;11;{refused('0001', '0Bh', '0000')};", "3;;;",
        "1;11;;", "2;11;;",
        f"1;3;{refused('3B01', '03h', 'a character, then 00')};", "3;;;",
        f"1;1;{refused('1234', '01h', '0000 or FF00')};", "3;;;",
        # (Return Query Data has no length rule: a record's end right after its CRC settles it, one pass too, 52cad27)
        "1;0;;", "2;0;;",
        f"1;20;{refused('FFFF', '14h', '0000')};", "3;;;",
    ]
    tree = tshark(pcap, "-V", "-Y", "frame.number == 1", two_pass=two_pass)
    assert "        [Expert Info (Note/Comment): clear the communications event log]\n" in tree
