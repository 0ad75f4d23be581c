"""The plugin's profiles and maps preferences refuse slave 0 (the broadcast address, which no device has) and
a slave past 247, as vw3-decode --profile 0=NAME and --map 0=FILE do (app/profile_options.py check_slaves).
Real tshark 4.0.17 with lua/vw3.lua."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import ROOT, lua_items

CAPTURE = ROOT / "captures" / "sel749m_polling.pcap"


@pytest.mark.parametrize(("option", "said"), [
    ("vw3.profiles:0=sel749m",
     'Preferences: "0=sel749m": slave 0 is the broadcast address, which no device has (a slave is 1..247)'),
    ("vw3.profiles:248=sel749m", "Preferences: slave 248 is outside 1..247"),
])
def test_profiles_preference_refuses_slave_0(option: str, said: str) -> None:
    _, record_experts, _ = lua_items(CAPTURE, "-o", option)
    assert {text for _, text in record_experts if text.startswith("Preferences")} == {said}


def test_maps_preference_refuses_slave_0(tmp_path: Path) -> None:
    sel = tmp_path / "sel.csv"
    sel.write_text("address,code,name\n0,IA,Phase A current\n")
    _, record_experts, _ = lua_items(CAPTURE, "-o", f"vw3.maps:0={sel}")
    assert {text for _, text in record_experts if text.startswith("Preferences")} == {
        f'Preferences: map "0={sel}": slave 0 is the broadcast address, which no device has (a slave is 1..247)'}
