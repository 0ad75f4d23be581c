"""The plugin says what vw3-decode says of an exception 02 to a write on the ATV71 (the card's "address does
not exist", without p.38's clause about reads; FC23 keeps it): tests/unit/test_atv71_write_exceptions.py's
frames under real tshark, one pass and two."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = ["0C 06 20D1 0003", "0C 86 02", "0C 10 0C81 0002 04 0001 0002", "0C 90 02",
          "0C 17 0C82 0002 20D1 0001 02 0003", "0C 97 02", "0C 03 20D0 0003", "0C 83 02"]
READS_TOO = "address does not exist (also: every parameter read is non-existent or protected)"


@pytest.mark.parametrize("two_pass", [True, False])
def test_exception_02_to_a_write(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "writes.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                 for index, frame in enumerate(FRAMES)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.note", "-e", "vw3.exception_meaning", "-Y", "vw3.kind == 3", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [
        f"2|exception 02 from the VW3 A3 303 to Write Single Register: address does not exist|{READS_TOO}",
        f"4|exception 02 from the VW3 A3 303 to Write Multiple Registers: address does not exist|{READS_TOO}",
        f"6|exception 02 from the VW3 A3 303: {READS_TOO}|{READS_TOO}",
        "8|exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
        f"8400 non-existent, CHCF (8401) protected, COP (8402) protected|{READS_TOO}",
    ]
