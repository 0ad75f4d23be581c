"""Bytes after a layout's data (data/modbus.toml: a layout not ending in `rest` ends in `trailing`): vw3-decode
keeps them (--json fields.trailing, -V `Trailing: aabb`, -Y fields.trailing) and warns `unexpected bytes after
the data (N)`; the plugin warned only, its tree had no item for the bytes. Now it shows them as vw3.trailing,
where -V has them (after the PDU's fields, before the registers, FC22's mask register included) and on an
exception (after its code, as --json, -Y and -V have them). Real tshark with -X lua_script:lua/vw3.lua."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import assert_same_frames, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
T0 = 1700000000.0

# (hex without its CRC, the trailing bytes vw3-decode keeps, as hex; "" none)
FRAMES = [
    ("01 06 0001 0003 AA BB", "aabb"),  # FC6 request: two bytes after its value
    ("01 03 0000 0001", ""),
    ("01 03 02 0005 AA BB", "aabb"),  # its answer: two bytes after the byte count's data
    ("01 16 0004 00F2 0025 CC", "cc"),  # FC22: one byte after the masks, its register after it
    ("01 10 0000 0001 02 0007 DD EE", "ddee"),  # FC16 request
    ("01 03 0000 0001", ""),
    ("01 83 02 00", "00"),  # an exception: a byte after its code
]


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("trailing") / "trailing.pcap",
                      [(rtu(hex_text), T0 + index * 0.5) for index, (hex_text, _) in enumerate(FRAMES)])


def _vw3_decode(*args: str) -> str:
    out = subprocess.run([sys.executable, "-m", "dissector", *args], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_vw3_decode_keeps_the_bytes(capture: Path) -> None:
    items = [json.loads(line) for line in _vw3_decode("--json", str(capture)).splitlines()]
    assert [item["fields"].get("trailing", "") for item in items] == [trailing for _, trailing in FRAMES]


def test_the_plugin_shows_them_as_vw3_trailing(capture: Path) -> None:
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-e", "vw3.trailing", "-e", "vw3.warning")
    assert not lua_errors(got.stdout + got.stderr)
    rows = [line.split("|") for line in got.stdout.splitlines()]
    assert [row[0] for row in rows] == [trailing for _, trailing in FRAMES]
    # (each with vw3-decode's warning, as before)
    assert [f"unexpected bytes after the data ({len(row[0]) // 2})" in row[1] for row in rows] == [
        bool(trailing) for _, trailing in FRAMES]


def test_the_tree_places_them_as_vw3_decode_does(capture: Path) -> None:
    """After the PDU's fields and before the registers, in both trees (the plugin's at depth 1, -V's at 2)."""
    got = run_tshark(capture, "-V", "-O", "vw3")
    assert not lua_errors(got.stdout + got.stderr)
    plugin = [[line for line in frame.splitlines() if line.startswith("    ") and not line.startswith("    [")
               and not line.startswith("     ")] for frame in got.stdout.split("\n\n") if frame.strip()]
    python = [[line for line in frame.splitlines() if line.startswith("        ")
               and not line.startswith("         ")] for frame in _vw3_decode("-V", str(capture)).split("\n\n")]
    assert plugin[0][-4:] == ["    Address: 1", "    Value: 3 (0x0003)", "    Trailing: aabb", "    Register 1 = 3"]
    assert python[0][-4:-1] == ["        Value: 3 (0x0003)", "        Trailing: aabb", "        Register 1: 3 (0x0003)"]
    assert plugin[2][-3:] == ["    Byte count: 2", "    Trailing: aabb", "    Register 0 = 5"]
    assert python[2][-4:-1] == ["        Byte count: 2 (0x2)", "        Trailing: aabb", "        Register 0: 5 (0x0005)"]
    assert plugin[3][-3:] == ["    OR mask: 37 (0x0025)", "    Trailing: cc",
                              "    Register 4: AND 0x00F2 OR 0x0025: the result depends on the value before"]
    assert python[3][-4:-1] == ["        OR mask: 37 (0x0025)", "        Trailing: cc", "        Register 4: no value"]
    assert plugin[4][-3:] == ["    Byte count: 2", "    Trailing: ddee", "    Register 0 = 7"]
    assert python[4][-4:-1] == ["        Byte count: 2 (0x2)", "        Trailing: ddee", "        Register 0: 7 (0x0007)"]
    # An exception's: after its code, in both trees (as --json and -Y have the byte).
    assert plugin[6][-2:] == ["    Exception code: Illegal Data Address (2)", "    Trailing: 00"]
    code = python[6].index("        Exception code: Illegal Data Address (2)")
    assert python[6][code + 1] == "        Trailing: 00"
    # Frames without: no item.
    assert not any("Trailing" in line for frame in (plugin[1], plugin[5]) for line in frame)


def test_filters_select_the_same_frames(capture: Path) -> None:
    assert_same_frames(capture, "fields.trailing", "vw3.trailing")
