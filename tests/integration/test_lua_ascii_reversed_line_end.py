"""The plugin shows a Modbus ASCII line ended LF then CR as vw3-decode does (tests/unit/
test_ascii_reversed_line_end.py): a frame that keeps the CR, with the warning 'line ends with LF then CR, reversed'
(before: 'line ends with LF without CR' and the CR a byte of noise). Real tshark with -X lua_script:lua/vw3.lua,
-2, the bytes in one record and a line a record; kinds, warnings and noise reasons as vw3-decode's, every field
as vw3-decode says it."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_compare import assert_same_as_vw3_decode
from lua_harness import ROOT, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_ascii_line_end_faults import ANSWER, READ, line  # noqa: E402
from test_ascii_reversed_line_end import REVERSED  # noqa: E402
from test_lua_ascii_line_end_faults import tshark  # noqa: E402

pytestmark = pytest.mark.integration

T0 = 1767225600.0


def test_lf_cr(tmp_path: Path) -> None:
    data = line(READ, b"\n\r") + line(ANSWER) + line(READ, b"\n\r")
    one = write_pcap(tmp_path / "one.pcap", [(data, T0)])
    assert tshark(one) == [f"1,2,1|{REVERSED},{REVERSED}|"]
    assert_same_as_vw3_decode(one)
    records = [b":" + part for part in data.split(b":")[1:]]
    each = write_pcap(tmp_path / "lines.pcap", [(record, T0 + 0.01 * at) for at, record in enumerate(records)])
    assert tshark(each) == [f"1|{REVERSED}|", "2||", f"1|{REVERSED}|"]
    assert_same_as_vw3_decode(each)


def test_an_lf_after_lf_cr_stays_noise(tmp_path: Path) -> None:
    one = write_pcap(tmp_path / "one.pcap", [(line(READ, b"\n\r\n") + line(ANSWER), T0)])
    assert tshark(one) == [f"1,4,2|{REVERSED}|outside an ASCII frame"]
    assert_same_as_vw3_decode(one)
