"""`!=` and `~=` in -Y mean what they mean in Wireshark (3.6 and later), checked against a real tshark
running the plugin on the same captures: `a != b` is all_ne (the field is there and no occurrence equals
b), `a ~= b` any_ne (some occurrence differs). A register field occurs once per register of a frame."""
from __future__ import annotations

import subprocess
import sys

import pytest

from lua_harness import ROOT, run_tshark

CASES = [
    # (vw3-decode -Y, tshark -Y with the plugin)
    ("value != 3", "vw3.reg.value != 3"),
    ("value ~= 3", "vw3.reg.value ~= 3"),
    ("value != 0", "vw3.reg.value != 0"),
    ("value any_ne 0", "vw3.reg.value ~= 0"),
    ('code != "CHCF"', 'vw3.reg.code != "CHCF"'),
    ('code ~= "CHCF"', 'vw3.reg.code ~= "CHCF"'),
    ('code != "CMD"', 'vw3.reg.code != "CMD"'),
    ('code ~= "CMD"', 'vw3.reg.code ~= "CMD"'),
    ("slave != 2", "vw3.slave != 2"),
]


def _frames(args: list[str]) -> list[int]:
    result = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    return [int(line) for line in result.stdout.split()]


@pytest.mark.parametrize("capture", ["p38_protection.pcap", "atv71_commissioning.pcap"])
@pytest.mark.parametrize(("ours", "wiresharks"), CASES)
def test_inequalities_select_the_frames_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    path = ROOT / "captures" / capture
    mine = _frames([sys.executable, "-m", "dissector", "-Y", ours, "-T", "fields", "-e", "frame", str(path)])
    result = run_tshark(path, "-Y", wiresharks, "-T", "fields", "-e", "frame.number")
    assert result.returncode == 0, result.stderr
    assert mine == [int(line) for line in result.stdout.split()]

