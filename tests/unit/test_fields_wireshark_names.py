"""-T fields -e with the field names a Wireshark user types (`tshark -T fields -e frame.number -e
frame.time_relative`, the plugin's `vw3.slave`, mbrtu's `mbrtu.unit_id`): -Y's error names vw3-decode's field
for them (test_wireshark_field_names), -e said "only fields.<key> names a key inside a value" or "not a field
(see the NDJSON keys in the README)" and left the user to find it (hunt64)."""
from __future__ import annotations

import pytest

from conftest import ROOT
from helpers import run_cli

CAPTURE = str(ROOT / "captures" / "p38_protection.pcap")


@pytest.mark.parametrize("name, ours", [
    ("frame.number", "record"), ("frame.time_relative", "time_relative"), ("frame.time_delta", "time_delta"),
    ("frame.time_delta_displayed", "time_delta_displayed"), ("frame.time_epoch", "time"),
    ("frame.len", "length"), ("vw3.slave", "slave"), ("vw3.reg.code", "code"),
    ("vw3.byte_count", "fields.byte_count"), ("mbrtu.unit_id", "slave"), ("modbus.func_code", "function"),
    ("modbus.regval_uint16", "value"),
])
def test_wireshark_name_is_named(name: str, ours: str) -> None:
    assert run_cli(["-T", "fields", "-e", name, CAPTURE]) == (
        2, "", f"vw3-decode: -e {name}: not a field (vw3-decode names it {ours})\n")
    # and the name given is one -e takes, with what tshark's field holds (frame 2 of p.38)
    status, out, err = run_cli(["-T", "fields", "-e", ours, "-Y", "frame == 2", CAPTURE])
    assert (status, err) == (0, "") and out.strip() != ""


def test_names_without_a_key_as_before() -> None:
    assert run_cli(["-T", "fields", "-e", "frame.protocols", CAPTURE])[2] == (
        "vw3-decode: -e frame.protocols: only fields.KEY names a key inside a value\n")
    assert run_cli(["-T", "fields", "-e", "_ws.col.Info", CAPTURE])[2] == (
        "vw3-decode: -e _ws.col.Info: not a field (see the NDJSON keys in the README)\n")
