"""The plugin on a request the capture ends after, as vw3-decode (tests/unit/test_capture_end_interfaces.py):
the capture ends with its last record of any stream, empty or not (lua/src/pairing.lua ended:
recorded_until). With VW3_INTERFACES=1 (each interface its own stream; tshark -2 needs -Y for it) bus A's
last request, bus B's records going on 2 s after it, is unanswered: 'Request not answered'; before, bus A's
own last record ended it ('not known whether it was answered'). So does an empty last record (pcapng, pcap).
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark

sys.path.insert(0, str(ROOT / "tests" / "unit"))  # (its captures: collected alone, it is not on the path)
from test_capture_end_interfaces import BUS_A, POLLS, REQUEST, _pcap, _two_buses  # noqa: E402
from test_pcapng_interfaces import _pcapng  # noqa: E402

FIELDS = ["-Y", "frame", "-T", "fields", "-E", "separator=;", "-e", "frame.interface_id", "-e", "vw3.kind",
          "-e", "vw3.unanswered", "-e", "vw3.note"]
PAST = "0;1;1;"
WITHIN = ("0;1;;the capture ends 200.0 ms after the request, within the 1000 ms timeout: not known "
          "whether it was answered")


def _fields(path: Path) -> list[str]:
    result = run_tshark(path, *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("until, last", [(3_012_000, PAST), (1_200_000, WITHIN)], ids=["past", "within"])
def test_other_interface_ends_the_wait(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, until: int,
                                       last: str) -> None:
    monkeypatch.setenv("VW3_INTERFACES", "1")
    rows = _fields(_two_buses(tmp_path / "two.pcapng", until))
    assert [row for row in rows if row.startswith("0;")] == ["0;1;;", "0;2;;", last]
    assert [row for row in rows if row.startswith("1;")] == ["1;1;;", "1;2;;"] * 2


@pytest.mark.parametrize("until, last", [(3_012_000, PAST), (1_200_000, WITHIN)], ids=["past", "within"])
def test_an_empty_last_record_ends_the_wait(tmp_path: Path, until: int, last: str) -> None:
    path = tmp_path / "one.pcapng"
    path.write_bytes(_pcapng(["A"], BUS_A + [(0, until, b"")]))
    assert _fields(path) == ["0;1;;", "0;2;;", last, "0;;;"]


@pytest.mark.parametrize("until, last", [(3_012_000, PAST), (1_200_000, WITHIN)], ids=["past", "within"])
def test_a_pcap_empty_last_record_too(tmp_path: Path, until: int, last: str) -> None:
    path = tmp_path / "one.pcap"
    path.write_bytes(_pcap(POLLS + [(1_000_000, REQUEST), (until, b"")]))
    assert _fields(path)[-2:] == [last[1:], ";;;"]  # (a pcap has no interface)
