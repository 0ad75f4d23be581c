"""The plugin names a 32-bit row's second register without its first as vw3-decode does
(tests/unit/test_wide_second_alone.py's frames): real tshark, one pass and two."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))  # (its frames: collected alone, that module is not on the path)
from test_wide_second_alone import ATV, FIRST_FREQ, MAP, SECOND_FREQ, SECOND_PWR, SEL  # noqa: E402

pytestmark = pytest.mark.integration


def _rows(pcap: Path, profile: str, table: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-o", f"vw3.profiles:{profile}", "-o", f"vw3.maps:{profile}={table}", "-T", "fields",
                     "-E", "separator=|", "-e", "frame.number", "-e", "vw3.reg.code", "-e", "vw3.reg.text",
                     "-e", "vw3.reg.status", "-Y", "vw3.kind == 2", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr
    return got.stdout.splitlines()


@pytest.mark.parametrize("two_pass", [True, False])
def test_second_word_alone(tmp_path: Path, two_pass: bool) -> None:
    table = tmp_path / "map.csv"
    table.write_text(MAP, encoding="utf-8")
    sel = write_pcap(tmp_path / "sel.pcap", [(rtu(frame), 1700000000 + index * 0.01) for index, frame in enumerate(SEL)])
    assert _rows(sel, "sel749m", table, two_pass) == [
        f"2|PWR,FREQ|{SECOND_PWR},{FIRST_FREQ}|,",  # (no status: the SEL-749M has no 16#8000 story)
        f"4|PWR|{SECOND_PWR}|",
        f"6|FREQ,|{SECOND_FREQ},|,",
    ]
    atv = write_pcap(tmp_path / "atv.pcap", [(rtu(frame), 1700000000 + index * 0.01) for index, frame in enumerate(ATV)])
    assert _rows(atv, "atv71", table, two_pass) == [
        f"2|PWR,FREQ,FREQ|{SECOND_PWR},50.02 Hz,second word of FREQ|ambiguous,ok,ok"]
