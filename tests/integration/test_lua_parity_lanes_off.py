"""The parity of test_lua_parity.py with the quick lanes off (`-o vw3.quick_lanes:FALSE`): every record
by the general path (framing, pairing, the generic lifter, annotation), which the lanes must equal. The
lanes on is the default those tests run; here the same captures, the same random RTU session and a
random ASCII session, against `vw3-decode --json`, zero differences either way."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_compare import compare
from lua_harness import ROOT, LuaItem, PythonItem, lua_items, python_items, write_pcap
from lua_session import SessionBuilder, ascii_session

OFF = ("-o", "vw3.quick_lanes:FALSE")
CAPTURES = sorted((ROOT / "captures").glob("*.pcap"))
PROFILES = {"sel749m_polling.pcap": ["1=sel749m"]}  # (as test_lua_parity.py: the captures' README)


def _check(python: list[PythonItem], lua: list[LuaItem]) -> None:
    differences = compare(python, lua)
    assert not differences, f"{len(differences)} differences, first ones:\n" + "\n".join(differences[:40])


@pytest.mark.parametrize("capture", CAPTURES, ids=[path.name for path in CAPTURES])
def test_capture_parity_without_the_quick_lanes(capture: Path) -> None:
    profiles = PROFILES.get(capture.name, [])
    options = ["-o", f"vw3.profiles:{','.join(profiles)}"] if profiles else []
    _check(python_items(capture, profiles), lua_items(capture, *options, *OFF)[0])


def test_random_session_parity_without_the_quick_lanes(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "session.pcap", SessionBuilder(seed=20261121).session(3000))
    python = python_items(pcap)
    _check(python, lua_items(pcap, *OFF)[0])
    # (the lanes on give the same items: the two runs differ only in the path the records took)
    _check(python, lua_items(pcap)[0])


def test_random_ascii_session_parity_without_the_quick_lanes(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "ascii.pcap", ascii_session(31, 1500))
    python = python_items(pcap)
    assert sum(item.data["kind"] != "noise" for item in python) > 2000
    _check(python, lua_items(pcap, *OFF)[0])
