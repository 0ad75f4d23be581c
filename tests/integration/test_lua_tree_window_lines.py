"""vw3-decode -V says what the plugin's tree says of an answer's window and of a hex field's width (hunt 56,
pymodbus 3.16.1 answering mbpoll): a read's answer shows the window its request gave it, `[Start address: 10]`
`[Quantity: 2]` (FC23's too), FC24's answer its request's `[FIFO pointer address: 7]` (before: none in -V);
a field shown in decimal and hex writes the hex at its width in the frame, as Wireshark writes the plugin's
uint16 field: FC11's and FC12's 16-bit status word `Status: 0 (0x0000)`, FC22's masks `(0x00F2)`, FC43's
more-follows byte `(0x00)` (before: `(0x0)`, `(0xF2)`). vw3-decode writes hex in upper case throughout, the
plugin as Wireshark does, in lower case: compared regardless of case. An answer whose request is not in the
capture shows no start address in either, the quantity its byte count gives in both (`[Quantity: 1]`, as
--json's `quantity`; before, -V showed none and the comparison left the plugin's out). Real tshark."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
T0 = 1767225600.0
FRAMES = [
    rtu("0C 04 000A 0002"), rtu("0C 04 04 000A 000B"),  # FC4 10..11
    rtu("01 01 0005 000D"), rtu("01 01 02 AA 0A"),  # FC1 5..17
    rtu("01 17 000A 0002 001E 0001 02 0007"), rtu("01 17 04 0001 0002"),  # FC23 read 10..11
    rtu("01 18 0007"), rtu("01 18 0006 0002 0001 0002"),  # FC24 pointer 7
    rtu("01 0B"), rtu("01 0B 0000 0003"),  # FC11 status 0
    rtu("01 0C"), rtu("01 0C 06 FFFF 0003 0005"),  # FC12 status 0xFFFF
    rtu("01 16 0028 00F2 0025"), rtu("01 16 0028 00F2 0025"),
    rtu("01 2B 0E 01 00"), rtu("01 2B 0E 01 01 00 00 01 00 03 41 42 43"),  # FC43/14, more follows 0
    rtu("01 03 02 0009"),  # an answer without its request: no start, its byte count's quantity
]
WANTED = ("[Start address", "[Quantity", "[FIFO pointer", "Status:", "AND mask", "OR mask", "More follows")
EXPECTED = [
    "[Start address: 10]", "[Quantity: 2]", "[Start address: 5]", "[Quantity: 13]",
    "[Start address: 10]", "[Quantity: 2]", "[FIFO pointer address: 7]", "Status: 0 (0x0000)",
    "Status: 65535 (0xFFFF)", "[Quantity: 1]", "AND mask: 242 (0x00F2)", "OR mask: 37 (0x0025)", "[Quantity: 1]",
    "AND mask: 242 (0x00F2)", "OR mask: 37 (0x0025)", "More follows: 0 (0x00)", "[Quantity: 1]",
]


def _lines(text: str) -> list[str]:
    # (FC1's `Status` is its coils' bytes: no number)
    return [line.strip() for line in text.splitlines() if line.strip().startswith(WANTED) and "Status: aa" not in line]


def test_vw3_decode_and_the_plugin_say_the_same(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "w.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    assert _lines(python) == EXPECTED
    assert ("Function: 4 (0x04) Read Input Registers\n        [Start address: 10]\n        [Quantity: 2]\n"
            "        Byte count: 4 (0x4)\n") in python
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    # (FC22's implied quantity of one, `[Quantity: 1]`, in both: test_lua_implied_quantity.py)
    assert [line.lower() for line in _lines(result.stdout)] == [line.lower() for line in EXPECTED]
