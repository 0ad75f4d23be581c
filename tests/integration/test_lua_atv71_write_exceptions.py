"""The plugin says what vw3-decode says of an exception 02 on the ATV71 (the card's "address does not exist";
to a read of registers, FC3 and FC23, p.38's clause too; to a write, FC5/6/15/16/22, not):
tests/unit/test_atv71_write_exceptions.py's frames under real tshark, one pass and two."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_atv71_write_exceptions import FRAMES, MEANINGS, NOTES  # noqa: E402

pytestmark = pytest.mark.integration


@pytest.mark.parametrize("two_pass", [True, False])
def test_exception_02_per_access(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "writes.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                 for index, frame in enumerate(FRAMES)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.note", "-e", "vw3.exception_meaning", "-Y", "vw3.kind == 3", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [f"{2 * index + 2}|{note}|{meaning}"
                                       for index, (note, meaning) in enumerate(zip(NOTES, MEANINGS))]
