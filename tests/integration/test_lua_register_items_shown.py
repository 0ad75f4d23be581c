"""Registers with no name, unit or value text (a user map's rows of a code alone, of a name, of a unit; an address
no row names) show in the plugin's tree what vw3-decode -V shows of them and no empty item: their text fields'
empty occurrences (vw3.reg.name, .unit, .text, ...) are hidden items, there only so that tshark -T fields lines
registers up as vw3-decode -T fields does (lua/README.md). A guard of that parity (the "plugin empty vw3.reg.*
items" of earlier reports: none found in -V on captures/, tests/corpus or these rows). Real tshark."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
T0 = 1700000000.0
MAP = "address,code,name,unit,scale\n1,A,,,\n2,B,Bee,,\n3,C,,V,\n"
FRAMES = [rtu("01 03 0001 0004"), rtu("01 03 08 0005 0006 0007 0008")]
# The answer's registers: vw3-decode -V's lines, the plugin's tree (tshark -V), register by register.
PYTHON = [
    ["Register 1: 5 (0x0005)  A"],
    ["Register 2: 6 (0x0006)  B [Bee]"],
    ["Register 3: 7 (0x0007)  C", "    Value: 7 V", "    Unit: V"],
    ["Register 4: 8 (0x0008)"],
]
PLUGIN = [
    ["Register 1 A = 5", "    [Address: 1]", "    Value: 5 (0x0005)", "    [Code: A]"],
    ["Register 2 B = 6", "    [Address: 2]", "    Value: 6 (0x0006)", "    [Code: B]", "    [Name: Bee]"],
    ["Register 3 C = 7: 7 V", "    [Address: 3]", "    Value: 7 (0x0007)", "    [Code: C]", "    [Unit: V]",
     "    [Scaled value: 7]", "    [Meaning: 7 V]"],
    ["Register 4 = 8", "    [Address: 4]", "    Value: 8 (0x0008)"],
]
TEXT_KEYS = ["code", "name", "unit", "text", "source", "label", "status"]


def _blocks(lines: list[str], indent: str) -> list[list[str]]:
    """The register blocks of a frame's lines: each `Register` line at `indent` and the deeper lines after it."""
    blocks: list[list[str]] = []
    open_block = False
    for line in lines:
        if line.startswith(indent + "Register "):
            blocks.append([line[len(indent):]])
            open_block = True
        elif open_block and line.startswith(indent + "    "):
            blocks[-1].append(line[len(indent):])
        else:
            open_block = False
    return blocks


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("unnamed")
    (folder / "map.csv").write_text(MAP, encoding="utf-8")
    pcap = write_pcap(folder / "unnamed.pcap", [(frame, T0 + 0.01 * index) for index, frame in enumerate(FRAMES)])
    return pcap, folder / "map.csv"


def test_the_tree_shows_what_vw3_decode_shows(capture: tuple[Path, Path]) -> None:
    pcap, csv = capture
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", "--map", str(csv), str(pcap)],
                            capture_output=True, text=True, check=True).stdout.split("\n\n")[1]
    assert _blocks(python.splitlines(), "        ") == PYTHON
    got = run_tshark(pcap, "-o", f"vw3.maps:{csv}", "-V", "-O", "vw3")
    assert not lua_errors(got.stdout + got.stderr)
    answer = got.stdout.split("\n\n")[1].splitlines()
    assert _blocks(answer, "    ") == PLUGIN
    assert not [line for line in answer if re.search(r": ?\]?$", line)]  # (no empty item shown)


def test_the_empty_occurrences_are_hidden_and_line_up(capture: tuple[Path, Path]) -> None:
    pcap, csv = capture
    pdml = run_tshark(pcap, "-o", f"vw3.maps:{csv}", "-T", "pdml").stdout
    empties = re.findall(r'<field name="vw3\.reg\.(\w+)"[^>]*show=""[^>]*>', pdml)
    assert empties and all('hide="yes"' in field for field in
                           re.findall(r'<field name="vw3\.reg\.\w+"[^>]*show=""[^>]*>', pdml))
    fields = [arg for key in TEXT_KEYS for arg in ("-e", f"vw3.reg.{key}")]
    plugin = run_tshark(pcap, "-o", f"vw3.maps:{csv}", "-T", "fields", "-E", "separator=|", *fields,
                        "-Y", "vw3.kind == 2").stdout.splitlines()
    python = subprocess.run([sys.executable, "-m", "dissector", "--map", str(csv), "-T", "fields", "-E",
                             "separator=|", *[arg for key in TEXT_KEYS for arg in ("-e", key)], "-Y",
                             'kind == "response"', str(pcap)], capture_output=True, text=True, check=True)
    assert plugin == python.stdout.splitlines() == ["A,B,C,|,Bee,,|,,V,|,,7 V,|,,,|,,,|,,,"]
