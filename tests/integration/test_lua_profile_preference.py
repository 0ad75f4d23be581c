"""The plugin's profiles preference reads a choice as `vw3-decode --profile` does.

`12 = atv71` (spaces around '=') is slave 12's profile in both; a slave address is ASCII digits in both:
`+1`, `1_0` (which Python's int() reads as 10) and other scripts' digits are refused, with the same
reason. Real tshark 4.0.17 with lua/vw3.lua against vw3-decode on captures/sel749m_polling.pcap.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

from lua_compare import compare
from lua_harness import ROOT, lua_items, python_items

CAPTURE = ROOT / "captures" / "sel749m_polling.pcap"


@pytest.mark.parametrize("choice", ["1 = sel749m", "1=sel749m ", " 1 =sel749m"])
def test_spaces_around_the_equals_sign_name_slave_1s_profile(choice: str) -> None:
    python = python_items(CAPTURE, [choice])
    lua, record_experts, _ = lua_items(CAPTURE, "-o", f"vw3.profiles:{choice}")
    assert not [text for _, text in record_experts if text.startswith("Preferences")]
    assert not compare(python, lua)
    # The choice took effect: the same items as 1=sel749m, which the default profile's differ from
    # (the SEL-749M's PLC references: 40001 for address 0)
    assert python == python_items(CAPTURE, ["1=sel749m"]) != python_items(CAPTURE, [])
    labels = {reg.get("label") for item in python for reg in item.data.get("registers", [])}
    assert "40001" in labels


@pytest.mark.parametrize("target", ["+1", "1_0", "\u0661"])
def test_a_slave_address_is_ascii_digits(target: str) -> None:
    choice = f"{target}=sel749m"
    decoded = subprocess.run(
        [sys.executable, "-m", "dissector", "--profile", choice, str(CAPTURE)],
        capture_output=True, encoding="utf-8", cwd=ROOT, timeout=120)
    assert decoded.returncode == 2
    assert decoded.stderr == f"vw3-decode: --profile {choice!r}: {target!r} is not a slave address\n"
    _, record_experts, _ = lua_items(CAPTURE, "-o", f"vw3.profiles:{choice}")
    said = {text for _, text in record_experts if text.startswith("Preferences")}
    assert said == {f'Preferences: "{choice}": "{target}" is not a slave address'}


def test_a_map_choice_with_spaces_around_the_equals_sign(tmp_path) -> None:
    # `--map "1 = FILE"` and the maps preference `1 = FILE`: slave 1's map, the path without the spaces
    sel = tmp_path / "sel.csv"
    sel.write_text("address,code,name\n0,IA,Phase A current\n")
    python = python_items(CAPTURE, ["1=sel749m"], "--map", f"1 = {sel}")
    lua, record_experts, _ = lua_items(CAPTURE, "-o", "vw3.profiles:1=sel749m", "-o", f"vw3.maps:1 = {sel}")
    assert not [text for _, text in record_experts if text.startswith("Preferences")]
    assert not compare(python, lua)
    codes = {reg.get("code") for item in python for reg in item.data.get("registers", [])}
    assert "IA" in codes
