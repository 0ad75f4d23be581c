"""--stats with -Y counts what the filter passes, as tshark -z with a filter: the Device profiles section
too (render/stats.py), and with -c N what was read. Before, it listed every slave profile `auto` chose over the whole input: slaves 1, 5
and 12 under `-Y "slave == 3"`, whose traffic, response time and parameter tables were empty.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

ROOT = Path(__file__).resolve().parents[2]
NOISY = str(ROOT / "captures" / "noisy_bus.pcap")  # slaves 1, 5 and 12
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
GENERIC = "generic  no evidence of a device: spec semantics only"


def _stats(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", *argv, NOISY])
    assert (status, err) == (0, "")
    return out


@BOTH
def test_profiles_of_the_slaves_the_filter_passes(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    lines = _stats(["-Y", "slave == 12"], monkeypatch, pure).splitlines()
    assert lines[:6] == ["16 frames, 0 noise bytes in 0 runs", "", "Device profiles", "slave  profile  why",
                         "-" * 60, f"   12  {GENERIC}"]
    assert lines[6:8] == ["", "Traffic per slave and function"]
    report = json.loads(_stats(["-Y", "slave == 12", "--json"], monkeypatch, pure))
    assert report["profiles"] == [{"slave": 12, "profile": "generic", "reason": GENERIC.split("  ")[1],
                                   "frame": None}]


@BOTH
def test_no_profile_section_when_nothing_passes(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    lines = _stats(["-Y", "slave == 3"], monkeypatch, pure).splitlines()
    assert lines[:3] == ["0 frames, 0 noise bytes in 0 runs", "", "Traffic per slave and function"]


def test_profiles_of_the_slaves_read_before_c_stops(monkeypatch: pytest.MonkeyPatch) -> None:
    lines = _stats(["-c", "6"], monkeypatch, False).splitlines()  # (slave 5 answers later)
    assert lines[2:7] == ["Device profiles", "slave  profile  why", "-" * 60, f"    1  {GENERIC}", f"   12  {GENERIC}"]


@BOTH
def test_unfiltered_stats_list_every_slave(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    lines = _stats([], monkeypatch, pure).splitlines()
    assert lines[2:8] == ["Device profiles", "slave  profile  why", "-" * 60, f"    1  {GENERIC}",
                          f"    5  {GENERIC}", f"   12  {GENERIC}"]
