"""`${FIELD}` in -Y, as tshark 4.0.17 reads it: a field reference, the field's value in the frame selected in
Wireshark's GUI; a decode (as tshark) has none selected, so it holds no value and no comparison with it holds
(==, !=, ===, all, a set member), while `not slave == ${slave}` holds everywhere. A name that is no field is
a display filter macro to tshark ("macro 'foo' does not exist"), a reference alone is no test: refused, as
tshark refuses them. Before, every `$` was 'unexpected character'. Against tshark with the plugin."""
from __future__ import annotations

import subprocess
import sys

import pytest

from lua_harness import ROOT, assert_same_frames, run_tshark

CASES = [
    ("noisy_bus.pcap", "slave == ${slave}", "vw3.slave == ${vw3.slave}"),
    ("noisy_bus.pcap", "slave != ${slave}", "vw3.slave != ${vw3.slave}"),
    ("noisy_bus.pcap", "${slave} == 12", "${vw3.slave} == 12"),
    ("noisy_bus.pcap", "not slave == ${slave}", "not vw3.slave == ${vw3.slave}"),
    ("noisy_bus.pcap", "slave == ${slave} or slave == 12", "vw3.slave == ${vw3.slave} or vw3.slave == 12"),
    ("noisy_bus.pcap", "slave in {12, ${slave}}", "vw3.slave in {12, ${vw3.slave}}"),
    ("noisy_bus.pcap", "slave in {1..${slave}}", "vw3.slave in {1..${vw3.slave}}"),
    ("noisy_bus.pcap", "slave < ${slave} + 1", "vw3.slave < ${vw3.slave} + 1"),
    ("atv71_commissioning.pcap", "all value == ${value}", "all vw3.reg.value == ${vw3.reg.value}"),
    ("atv71_commissioning.pcap", "value === ${value}", "vw3.reg.value === ${vw3.reg.value}"),
]
REFUSED = [
    ("${foo} == 1", "${foo} == 1", "vw3-decode: macro 'foo' does not exist"),
    ("slave == ${slave", "vw3.slave == ${vw3.slave", "vw3-decode: unexpected character '$'"),
    ("${slave}", "${vw3.slave}", "vw3-decode: ${slave} is a field reference, no test"),
    ("slave == ${}", "vw3.slave == ${}", "vw3-decode: macro '' does not exist"),
    ("slave == $slave", "vw3.slave == $vw3.slave", "vw3-decode: unexpected character '$'"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_selects_what_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


@pytest.mark.parametrize(("ours", "wiresharks", "said"), REFUSED)
def test_refused_where_tshark_refuses(ours: str, wiresharks: str, said: str) -> None:
    path = ROOT / "captures" / "noisy_bus.pcap"
    mine = subprocess.run([sys.executable, "-m", "dissector", "-Y", ours, str(path)],
                          capture_output=True, text=True, timeout=300)
    assert (mine.returncode, mine.stdout) == (2, "") and "Traceback" not in mine.stderr
    lines = mine.stderr.splitlines()
    assert lines[0].startswith(said) and lines[1] == f"  {ours}" and lines[2].strip() == "^"
    result = run_tshark(path, "-Y", wiresharks)
    assert result.returncode != 0 and result.stdout == ""
