"""`vw3-decode -T fields -e KEY` for every register key writes what `tshark -T fields -e vw3.reg.KEY` writes
with the plugin, frame for frame, on every shipped capture: a number key (value, scaled, words) only
the values there are, a text key (code, name, status, label...) one occurrence per carried register
(empty where it has none), a read window's addresses in `address` and nothing of them in the others.
Before: a read request's window gave every other key an empty occurrence per address (`,,,` where
tshark writes nothing) and a register without a scaled value an empty one (`4,,` where tshark writes
`4`): 43 to 86 lines of atv71_commissioning differed per key."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, run_tshark, write_pcap

KEYS = ["address", "value", "code", "name", "unit", "scaled", "text", "status", "source", "label", "words"]
CAPTURES = sorted((ROOT / "captures").glob("*.pcap"))


def both(path: Path, *options: str) -> tuple[list[str], list[str]]:
    mine = subprocess.run([sys.executable, "-m", "dissector", str(path), "-T", "fields", *options,
                           *[x for key in ["frame", *KEYS] for x in ("-e", key)]],
                          capture_output=True, text=True, timeout=300)
    assert (mine.returncode, mine.stderr) == (0, "")
    theirs = run_tshark(path, "-T", "fields", *options,
                        *[x for name in ["vw3.item", *(f"vw3.reg.{k}" for k in KEYS)] for x in ("-e", name)])
    assert theirs.returncode == 0, theirs.stderr
    return mine.stdout.splitlines(), theirs.stdout.splitlines()


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.name)
def test_every_register_key_as_tshark_writes_it(capture: Path) -> None:
    mine, theirs = both(capture, "-E", "aggregator=^")
    assert len(mine) == len(theirs) > 0
    assert mine == theirs


@pytest.mark.parametrize("occurrence", ["a", "f", "l"])
def test_a_read_and_write_request(tmp_path: Path, occurrence: str) -> None:
    """FC23 reading 0..1 and writing 16 = 7: 16,0,1 | 7 | (no scaled) | one empty code (register 16's)."""
    path = write_pcap(tmp_path / "fc23.pcap", [(rtu("17 17 0000 0002 0010 0001 02 00 07"), 1767225600.0)])
    mine, theirs = both(path, "-E", f"occurrence={occurrence}")
    address = {"a": "16,0,1", "f": "16", "l": "1"}[occurrence]
    assert mine == theirs == [f"1\t{address}\t7" + "\t" * (len(KEYS) - 2)]
