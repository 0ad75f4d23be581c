"""`all FIELD in {SET}` with a negative bound for an unsigned field, as tshark 4.0.17 reads it: under all,
the negative bound's comparison holds for every value (as `all slave > -1` and `all slave < -1` both
hold wherever slave is), the other bound is checked: `all slave in {-1..20}` is `all slave <= 20`,
`all slave in {-5..-1}` and `{-1}` hold wherever slave is. Before, such a member held no value (as under
any, where tshark selects nothing: kept). Against tshark with the plugin on the shipped captures."""
from __future__ import annotations

import pytest

from helpers import rtu, run_cli
from lua_harness import ROOT, assert_same_frames

CASES = [
    ("noisy_bus.pcap", "all slave in {-1..20}", "all vw3.slave in {-1..20}"),
    ("noisy_bus.pcap", "all slave in {-1..12}", "all vw3.slave in {-1..12}"),
    ("noisy_bus.pcap", "all slave in {-5..-1}", "all vw3.slave in {-5..-1}"),
    ("noisy_bus.pcap", "all slave in {-1}", "all vw3.slave in {-1}"),
    ("noisy_bus.pcap", "all slave in {13..-1}", "all vw3.slave in {13..-1}"),
    ("noisy_bus.pcap", "any slave in {-1..20}", "any vw3.slave in {-1..20}"),
    ("atv71_commissioning.pcap", "all value in {-1..3}", "all vw3.reg.value in {-1..3}"),
    ("atv71_commissioning.pcap", "all value in {-3..-1, 2}", "all vw3.reg.value in {-3..-1, 2}"),
    ("atv71_commissioning.pcap", "all value in {-1}", "all vw3.reg.value in {-1}"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_as_tshark(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


def frames(expression: str, stream: str) -> list[str]:
    status, out, err = run_cli(["-Y", expression, "-T", "fields", "-e", "frame", "--hex", stream])
    assert (status, err) == (0, "")
    return out.split()


def test_exact_frames() -> None:
    stream = " ".join(rtu(text).hex() for text in ("01 03 0000 0002", "01 03 04 0001 0007", "09 03 0000 0001"))
    assert frames("all slave in {-1..5}", stream) == ["1", "2"]  # (was none)
    assert frames("all slave in {-1}", stream) == ["1", "2", "3"]  # (was none)
    assert frames("all value in {-1..5}", stream) == []  # 7 is past 5
    assert frames("all value in {-1..7}", stream) == ["2"]  # (was none)
    assert frames("slave in {-1..5}", stream) == []  # (any: as before, as tshark)
