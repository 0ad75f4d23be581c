"""-Y sets with fields among their members, as tshark 4.0.17 reads them (`value in {address, 40}`,
`slave in {max(value)}`, `frame in {slave..200}`): each occurrence of the field meets each occurrence of a
member over the frame; `all` holds where some member holds for every occurrence; a range's bound that is
absent holds nothing (tshark 4.0.17 aborts on one with several values: vw3-decode's member holds
nothing then). Before: every field member was refused ("value is a number, not 'address'"). Against
tshark with the plugin; a member of another type, or with arithmetic, is refused by both."""
from __future__ import annotations

import subprocess
import sys

import pytest

from lua_harness import ROOT, assert_refused_as_tshark, assert_same_frames

ATV, NOISY = "atv71_commissioning.pcap", "noisy_bus.pcap"
CASES = [
    (ATV, "value in {value}", "vw3.reg.value in {vw3.reg.value}"),
    (ATV, "value in {address, 40}", "vw3.reg.value in {vw3.reg.address, 40}"),
    (ATV, "value in {slave}", "vw3.reg.value in {vw3.slave}"),
    (ATV, "value in {max(value)}", "vw3.reg.value in {max(vw3.reg.value)}"),
    (ATV, "value in {count(value)}", "vw3.reg.value in {count(vw3.reg.value)}"),
    (ATV, "all value in {value}", "all vw3.reg.value in {vw3.reg.value}"),
    (ATV, "all value in {2, value}", "all vw3.reg.value in {2, vw3.reg.value}"),
    (ATV, "all value in {0..100, value}", "all vw3.reg.value in {0..100, vw3.reg.value}"),
    (ATV, "value in {slave..600}", "vw3.reg.value in {vw3.slave..600}"),
    (ATV, "all value in {slave..600}", "all vw3.reg.value in {vw3.slave..600}"),
    (ATV, "value in {0..slave}", "vw3.reg.value in {0..vw3.slave}"),
    (ATV, "slave in {max(value)}", "vw3.slave in {max(vw3.reg.value)}"),
    (ATV, 'code in {name, "CHCF"}', 'vw3.reg.code in {vw3.reg.name, "CHCF"}'),
    (ATV, "not value in {address}", "not vw3.reg.value in {vw3.reg.address}"),
    (ATV, "address in {address}", "vw3.reg.address in {vw3.reg.address}"),
    (NOISY, "slave in {slave}", "vw3.slave in {vw3.slave}"),
    (NOISY, "frame in {slave..200}", "vw3.item in {vw3.slave..200}"),
    (NOISY, "frame in {0..slave}", "vw3.item in {0..vw3.slave}"),
    (NOISY, "frame in {1, 34, slave}", "vw3.item in {1, 34, vw3.slave}"),
    (NOISY, "slave in {function, 12}", "vw3.slave in {vw3.function, 12}"),
    (NOISY, "slave in {slave#2, 12}", "vw3.slave in {vw3.slave#2, 12}"),
]
REFUSED = [
    ("value in {code}", "vw3.reg.value in {vw3.reg.code}", "vw3-decode: value and code are not of compatible types"),
    ("value in {value + 1}", "vw3.reg.value in {vw3.reg.value + 1}", "vw3-decode: '+' was unexpected in this context"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_selects_what_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


@pytest.mark.parametrize(("ours", "wiresharks", "said"), REFUSED)
def test_refused_where_tshark_refuses(ours: str, wiresharks: str, said: str) -> None:
    path = ROOT / "captures" / ATV
    assert_refused_as_tshark(path, ours, wiresharks, said)


def test_a_range_bound_of_several_values_holds_nothing() -> None:
    """(tshark 4.0.17 aborts on it: `vw3.reg.value in {vw3.reg.value..600}`, an assertion in dfvm.c)"""
    path = ROOT / "captures" / ATV
    mine = subprocess.run([sys.executable, "-m", "dissector", "-Y", "value in {value..600}", "-T", "fields",
                           "-e", "frame", str(path)], capture_output=True, text=True, timeout=300)
    single = subprocess.run([sys.executable, "-m", "dissector", "-Y", "count(value) == 1 and value <= 600", "-T",
                             "fields", "-e", "frame", str(path)], capture_output=True, text=True, timeout=300)
    assert mine.returncode == single.returncode == 0 and mine.stdout == single.stdout != ""
