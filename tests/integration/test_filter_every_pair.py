"""-Y with register fields on both sides of one relation, as tshark 4.0.17 reads it: every occurrence of
the left meets every occurrence of the right, over the frame's registers (`value == address`, `value -
1 == value`), not register by register: `==` some pair equal, `!=` none, `===` every pair equal, `~=`
some pair differs, `<`... some pair, `all`/`any` as ===/==. Before, both sides read one register at a
time: `value ~= value` held nowhere, `value === value` everywhere, `value - 1 == value` nowhere (tshark:
82, 14 and 1 frames of atv71_commissioning). Against tshark with the plugin."""
from __future__ import annotations

import pytest

from lua_harness import ROOT, assert_same_frames

ATV, SEL, P38 = "atv71_commissioning.pcap", "sel749m_polling.pcap", "p38_protection.pcap"
CASES = [
    (ATV, "value == value", "vw3.reg.value == vw3.reg.value"),
    (ATV, "value === value", "vw3.reg.value === vw3.reg.value"),
    (ATV, "value ~= value", "vw3.reg.value ~= vw3.reg.value"),
    (ATV, "value != value", "vw3.reg.value != vw3.reg.value"),
    (ATV, "value > value", "vw3.reg.value > vw3.reg.value"),
    (ATV, "value < value", "vw3.reg.value < vw3.reg.value"),
    (ATV, "all value == value", "all vw3.reg.value == vw3.reg.value"),
    (ATV, "any value != value", "any vw3.reg.value != vw3.reg.value"),
    (ATV, "all value >= value", "all vw3.reg.value >= vw3.reg.value"),
    (ATV, "any value > value", "any vw3.reg.value > vw3.reg.value"),
    (ATV, "value == address - 8495", "vw3.reg.value == vw3.reg.address - 8495"),
    (ATV, "value - 1 == value", "vw3.reg.value - 1 == vw3.reg.value"),
    (ATV, "abs(value - value) > 5", "abs(vw3.reg.value - vw3.reg.value) > 5"),
    (ATV, "code ~= code", "vw3.reg.code ~= vw3.reg.code"),
    (ATV, "code === code", "vw3.reg.code === vw3.reg.code"),
    (ATV, "scaled > scaled", "vw3.reg.scaled > vw3.reg.scaled"),
    (ATV, "not value ~= value", "not vw3.reg.value ~= vw3.reg.value"),
    (ATV, "address === address", "vw3.reg.address === vw3.reg.address"),
    (SEL, "value ~= address", "vw3.reg.value ~= vw3.reg.address"),
    (SEL, "all value < address", "all vw3.reg.value < vw3.reg.address"),
    (SEL, "value ~= value + 0", "vw3.reg.value ~= vw3.reg.value + 0"),
    (P38, "value > value or value == 1", "vw3.reg.value > vw3.reg.value or vw3.reg.value == 1"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_selects_what_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)
