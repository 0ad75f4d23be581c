"""An FC22 frame's register (tree.lua add_pdu, as vw3-decode --json lists it) carries its address: the
plugin adds no hidden window address beside it (show.lua add_named), so `-e vw3.reg.address` is `40` as
vw3-decode's `-e address`, not `40,40`. Real tshark -2."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

FRAMES = ["01 16 0028 00F2 0025", "01 16 0028 00F2 0025", "01 16 0029 0000 0025", "01 16 0029 0000 0025"]


def test_one_address_as_vw3_decode(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "mask.pcap", [(rtu(frame), 1767225600 + 0.01 * index)
                                               for index, frame in enumerate(FRAMES)])
    ours = subprocess.run([sys.executable, "-m", "dissector", "-T", "fields", "-e", "address", "-e", "value",
                           str(pcap)], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    assert ours.splitlines() == ["40\t", "40\t", "41\t37", "41\t37"]
    got = run_tshark(pcap, "-T", "fields", "-e", "vw3.reg.address", "-e", "vw3.reg.value")
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    assert got.stdout.splitlines() == ours.splitlines()
