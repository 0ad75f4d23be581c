"""`--hex` reads each line of an argument as the hex dump reader reads a file's (sources/hexdump.py parse_line): an
NModbus log line's `TX:`/`RX:` label, a leading time stamp (the typed frame stays untimed) and a `# note` are passed
over, so a line pasted from an NModbus log decodes as the same line in a file does. Before, --hex refused them
(`--hex: 'TX:' is not hex`, `--hex: '10:00:00.125' is not hex`) while the file reader took them."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli

TX, RX = "TX: 1, 3, 0, 22, 0, 2, 37, 207", "RX: 1, 3, 4, 0, 1, 0, 2, 42, 50"
PAIR = (
    "     1            -   1 request   Read Holding Registers 22..23 (2)  CRC ok\n"
    "     2            -   1 response  Read Holding Registers 22..23 (2): 22=1 23=2 [#1]  CRC ok\n"
)


@pytest.mark.parametrize("arguments", [
    ["--hex", TX, "--hex", RX],
    ["--hex", f"{TX}\n{RX}"],  # (both lines pasted as one argument: two frames with good CRCs, fed as typed)
    ["--hex", f"10:00:00.125 {TX}", "--hex", f"10:00:00.135 {RX}"],
    ["--hex", f"{TX}  # poll", "--hex", f"rx: 1, 3, 4, 0, 1, 0, 2, 42, 50"],
])
def test_nmodbus_lines_typed(arguments: list[str], tmp_path: Path) -> None:
    assert run_cli(["-n", *arguments]) == (0, PAIR, "")
    path = tmp_path / "nmodbus.log"
    path.write_text(f"{TX}\n{RX}\n")
    assert run_cli(["-n", str(path)]) == (0, PAIR, "")


@pytest.mark.parametrize("typed, said", [
    ("TX:", "vw3-decode: --hex: 'TX:' without data\n"),
    ("TX: 1, 3, 999", "vw3-decode: --hex: '999' is not a byte (0..255)\n"),
    ("TX: 1, 3, 0x16", "vw3-decode: --hex: '1' is an odd number of hex digits\n"),
])
def test_bad_lines_refused_in_one_line(typed: str, said: str) -> None:
    assert run_cli(["-n", "--hex", typed]) == (2, "", said)
