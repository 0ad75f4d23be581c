"""The plugin's window fields point at the bytes they were read from: a request's vw3.start and vw3.quantity
at bytes 2-3 and 4-5 (`00 03`, as vw3-decode -V's `Quantity: 3 (0x3)`), not the whole frame; an answer's,
taken from its request, are generated and on no bytes of the answer; FC23's request names them as vw3-decode
-V does (`Read start: 3201`, `Read quantity: 2`). Real tshark with the plugin."""
from __future__ import annotations

import re

import pytest

from lua_harness import ROOT, lua_errors, run_tshark

pytestmark = pytest.mark.integration

_WINDOW = re.compile(r'<field name="vw3\.(start|quantity)" showname="([^"]*)" size="(\d+)" pos="(\d+)"')


def test_read_window_ranges_in_pdml() -> None:
    got = run_tshark(ROOT / "captures" / "p38_protection.pcap", "-T", "pdml", "-Y", "frame.number <= 2")
    assert not lua_errors(got.stdout + got.stderr)
    assert _WINDOW.findall(got.stdout) == [
        ("start", "Start address: 8400", "2", "2"), ("quantity", "Quantity: 3", "2", "4"),
        ("start", "Start address: 8400", "0", "0"), ("quantity", "Quantity: 3", "0", "0"),
    ]


def test_fc23_read_window_named_as_vw3_decode() -> None:
    got = run_tshark(ROOT / "captures" / "atv71_commissioning.pcap", "-V", "-Y", "frame.number == 19 || frame.number == 20")
    lines = [line.strip() for line in got.stdout.splitlines()
             if re.match(r"\s+\[?(Read |Write )?(start|Start address|quantity|Quantity)", line)]
    assert lines == ["Read start: 3201", "Read quantity: 2", "Write start: 8501", "Write quantity: 2",
                     "[Start address: 3201]", "[Quantity: 2]"]
