"""-Y's field references with a layer (`${slave#1}`) and bitwise and of two operands (`slave & ${slave}`,
`value & value`), as tshark 4.0.17 reads them: a reference holds no value in a decode (no selected
frame), with or without a layer; `&` with a field, a reference, a call or {...} on its right is an
operation (each occurrence of the left with each of the right), true where some result is not 0. A
name before # that is no field is a macro name to tshark, in which # is an invalid character; a
layer is read as slave#1's (`#1a`, `#-1`, an overflow refused). Before: all of these were refused
(macro 'slave#1' does not exist; slave takes a number...). Against tshark with the plugin."""
from __future__ import annotations


import pytest

from lua_harness import ROOT, assert_refused_as_tshark, assert_same_frames

NOISY, ATV = "noisy_bus.pcap", "atv71_commissioning.pcap"
CASES = [
    (NOISY, "slave & ${slave}", "vw3.slave & ${vw3.slave}"),
    (NOISY, "not slave & ${slave}", "not vw3.slave & ${vw3.slave}"),
    (NOISY, "${slave} & 1", "${vw3.slave} & 1"),
    (NOISY, "${slave#1} == 1", "${vw3.slave#1} == 1"),
    (NOISY, "slave == ${slave#1}", "vw3.slave == ${vw3.slave#1}"),
    (NOISY, "not slave == ${slave#1}", "not vw3.slave == ${vw3.slave#1}"),
    (NOISY, "slave == ${slave#[1-2]}", "vw3.slave == ${vw3.slave#[1-2]}"),
    (NOISY, "slave in {${slave#1}, 12}", "vw3.slave in {${vw3.slave#1}, 12}"),
    (NOISY, "slave & ${slave#1}", "vw3.slave & ${vw3.slave#1}"),
    (NOISY, "slave & slave", "vw3.slave & vw3.slave"),
    (NOISY, "slave & function", "vw3.slave & vw3.function"),
    (NOISY, "slave & {slave}", "vw3.slave & {vw3.slave}"),
    (NOISY, "slave & max(slave)", "vw3.slave & max(vw3.slave)"),
    (ATV, "value & value", "vw3.reg.value & vw3.reg.value"),
    (ATV, "value & address", "vw3.reg.value & vw3.reg.address"),
]
REFUSED = [
    ("slave == ${foo#1}", "vw3.slave == ${foo#1}", "vw3-decode: invalid character in macro name"),
    ("slave == ${slave #1}", "vw3.slave == ${vw3.slave #1}", "vw3-decode: invalid character in macro name"),
    ("slave == ${slave:1}", "vw3.slave == ${vw3.slave:1}", "vw3-decode: macro 'slave' does not exist"),
    ("slave == ${slave#1a}", "vw3.slave == ${vw3.slave#1a}", "vw3-decode: unexpected 'a' in the field reference"),
    ("slave == ${slave#-1}", "vw3.slave == ${vw3.slave#-1}", 'vw3-decode: expected digit or "[" after #'),
    ("slave == ${slave#99999999999}", "vw3.slave == ${vw3.slave#99999999999}",
     "vw3-decode: '99999999999' causes an integer overflow"),
    ("slave#2147483648 == 12", "vw3.slave#2147483648 == 12", "vw3-decode: '2147483648' causes an integer overflow"),
    ("${slave#1}", "${vw3.slave#1}", "vw3-decode: ${slave#1} is a field reference, no test"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_selects_what_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


@pytest.mark.parametrize(("ours", "wiresharks", "said"), REFUSED)
def test_refused_where_tshark_refuses(ours: str, wiresharks: str, said: str) -> None:
    path = ROOT / "captures" / NOISY
    assert_refused_as_tshark(path, ours, wiresharks, said)
