"""The plugin's Info column names an exception by the spec, as vw3-decode's summary does (`exception 2
(Illegal Data Address)`); the device's meaning stays its field vw3.exception_meaning and its note (p.38 of
the VW3 A3 303 manual: every parameter read non-existent or protected). Real tshark with the plugin."""
from __future__ import annotations

import pytest

from lua_harness import ROOT, lua_errors, run_tshark

pytestmark = pytest.mark.integration


def test_exception_info_names_the_spec_exception() -> None:
    got = run_tshark(ROOT / "captures" / "p38_protection.pcap", "-T", "fields", "-e", "frame.number",
                     "-e", "_ws.col.Info", "-e", "vw3.exception_meaning", "-Y", "vw3.kind == 3")
    assert not lua_errors(got.stdout + got.stderr)
    meaning = "address does not exist (also: every parameter read is non-existent or protected)"  # (p.38: a read)
    assert got.stdout.splitlines() == [
        f"10\t12 Read Holding Registers exception 2 (Illegal Data Address)\t{meaning}",
        f"12\t12 Read Holding Registers exception 2 (Illegal Data Address)\t{meaning}",
    ]
