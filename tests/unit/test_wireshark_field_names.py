"""-Y with the field names a Wireshark user has in their filters (hunt 58): the plugin's `vw3.slave`,
`vw3.reg.code` and tshark's `mbrtu.unit_id` were refused as unknown fields
and no word of the name vw3-decode gives the field (only frame.X had one). The error names it now."""
from __future__ import annotations

import subprocess

import pytest

from conftest import ROOT
from helpers import run_cli
from lua_harness import ensure_tool

CAPTURE = str(ROOT / "captures" / "p38_protection.pcap")


@pytest.mark.parametrize("name, ours", [
    ("vw3.slave == 12", "slave"), ('vw3.reg.code == "CHCF"', "code"), ("vw3.noise.reason", "reason"),
    ("vw3.byte_count == 6", "fields.byte_count"), ("mbrtu.unit_id == 12", "slave"),
    ("modbus.func_code == 3", "function"), ("modbus.regval_uint16 == 3", "value"),
    ("frame.time_epoch > 0", "time"), ("frame.len == 8", "length"),
])
def test_wireshark_name_is_named(name, ours):
    status, out, err = run_cli(["-Y", name, CAPTURE])
    field = name.split()[0]
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == (f"vw3-decode: unknown field {field!r}: only fields.KEY names a key inside a value"
                                   f" (vw3-decode names it {ours}) (column 1)")


def test_every_name_given_is_a_field():
    from dissector.render.filter_fields import FOREIGN_NAMES

    for ours in set(FOREIGN_NAMES.values()):
        status, _out, err = run_cli(["-Y", ours, "-c", "1", CAPTURE])
        assert (status, err) == (0, ""), ours


def test_tsharks_names_are_tsharks():
    """The mbrtu and modbus names are those tshark 4.0 has (a typo would name a field no one types)."""
    ensure_tool("tshark", "tshark")  # (a missing tool fails, never skips)
    from dissector.render.filter_fields import FOREIGN_NAMES

    glossary = subprocess.run(["tshark", "-G", "fields"], capture_output=True, text=True, check=True).stdout
    known = {line.split("\t")[2] for line in glossary.splitlines() if line.startswith("F\t")}
    ours = [name for name in FOREIGN_NAMES if not name.startswith("vw3.")]
    assert ours and [name for name in ours if name not in known] == []


def test_g_alone_is_g_fields():
    """tshark -G with no report lists the fields; `vw3-decode -G` was refused (expected one argument)."""
    fields = run_cli(["-G", "fields"])
    assert fields[0] == 0 and fields[1].startswith("P\tVW3 Modbus serial")
    assert run_cli(["-G"]) == fields
