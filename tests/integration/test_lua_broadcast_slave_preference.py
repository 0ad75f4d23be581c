"""The plugin's profiles and maps preferences refuse a slave past 247, and take unit 0: over Modbus/TCP, which
the plugin reads too (test_lua_modbus_tcp_adus), unit 0 is a device's address, where vw3-decode, serial
lines only, refuses --profile 0=NAME and --map 0=FILE (slave 0 is the broadcast address there:
app/profile_options.py check_slaves). Real tshark 4.0.17 with lua/vw3.lua."""
from __future__ import annotations

from pathlib import Path

from lua_harness import ROOT, lua_items

CAPTURE = ROOT / "captures" / "sel749m_polling.pcap"


def preference_errors(*options: str) -> set[str]:
    _, record_experts, _ = lua_items(CAPTURE, *options)
    return {text for _, text in record_experts if text.startswith("Preferences")}


def test_profiles_preference_refuses_slave_past_247() -> None:
    assert preference_errors("-o", "vw3.profiles:248=sel749m") == {"Preferences: slave 248 is outside 0..247"}
    assert preference_errors("-o", "vw3.profiles:0=sel749m") == set()


def test_maps_preference_refuses_slave_past_247(tmp_path: Path) -> None:
    sel = tmp_path / "sel.csv"
    sel.write_text("address,code,name\n0,IA,Phase A current\n")
    assert preference_errors("-o", f"vw3.maps:248={sel}") == {
        f'Preferences: map "248={sel}": slave 248 is outside 0..247'}
    assert preference_errors("-o", f"vw3.maps:0={sel}") == set()
