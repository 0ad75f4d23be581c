"""`${FIELD}` in -Y, as tshark 4.0.17 reads it: a field reference, the field's value in the frame selected in
Wireshark's GUI; a decode (as tshark) has none selected, so it holds no value and no comparison with it holds
(==, !=, ===, all, a set member), while `not slave == ${slave}` holds everywhere. A name that is no field is
a display filter macro to tshark ("macro 'foo' does not exist"), a reference alone is no test: refused, as
tshark refuses them. Before, every `$` was 'unexpected character'. Against tshark with the plugin."""
from __future__ import annotations


import pytest

from lua_harness import ROOT, assert_refused_as_tshark, assert_same_frames

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
    assert_refused_as_tshark(path, ours, wiresharks, said)
