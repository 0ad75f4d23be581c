"""Maps as spreadsheets save them, what vw3-decode and the plugin's `vw3.maps` say alike (hunt62).

A --map row whose quoted cell is not closed on its line (hunt62): a spreadsheet cell with a line break
(Excel's Alt+Enter, LibreOffice's Ctrl+Enter) is saved as a quoted field over two lines. Before, the row
was read up to its line end: `2 fields, the header has 4 (quote a field that holds a comma)` on a row whose
fields were quoted, or (the break in the last column) the row taken with half its cell and the next line
refused as `1 fields`, or (a closing quote forgotten) the rest of the line silently one cell. Now that
line is refused by its number, in vw3-decode and in the plugin's `vw3.maps` alike.

A map saved as Excel's "Unicode Text" (UTF-16 with its byte order mark, tab separated) was `not UTF-8
text`; it now says what it is and what to save instead."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_items, write_pcap
from dissector.protocol.crc import with_crc

pytestmark = pytest.mark.integration
OPEN = "a quoted field is not closed on this line (a line break inside a cell? write each row on one line)"
READ = [(with_crc(bytes.fromhex("010300000002")), 1767225600.0),
        (with_crc(bytes.fromhex("0103040001000A")), 1767225600.01)]


@pytest.mark.parametrize("text, line", [
    ('address,code,name,unit\r\n1,A,"Motor\nspeed",Hz\r\n2,B,Torque,%\r\n', 2),  # Excel: CR LF rows, LF in the cell
    ('address,code,name\n0,A,x\n1,B,"two\nlines"\n', 3),  # the break in the last column
    ('address,code,name\n1,A,"closing quote forgotten, here\n', 2),
    ('address,code,"name\n', 1),  # the header too
    ('address;code;name\n1;A;"say ""hi""""\n', 2),  # doubled quotes, the last one left open
])
def test_an_open_quote_is_refused_by_its_line(tmp_path: Path, text: str, line: int) -> None:
    bad = tmp_path / "map.csv"
    bad.write_bytes(text.encode())
    pcap = write_pcap(tmp_path / "read.pcap", READ)
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", f"1={bad}"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert (cli.returncode, cli.stdout, cli.stderr) == (2, "", f"vw3-decode: {bad}:{line}: {OPEN}\n")
    _, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:1={bad}")
    assert any(text.endswith(f"{bad}:{line}: {OPEN}") for _, text in record_experts), record_experts


def test_closed_quotes_still_read(tmp_path: Path) -> None:
    # a quote inside an unquoted cell is a character; "" inside a quoted one is a quote; a separator
    # inside quotes is the cell's
    good = tmp_path / "map.csv"
    good.write_text('address,code,name\n0,A,"x, ""y"""\n1,B,ab"c\n', encoding="utf-8")
    pcap = write_pcap(tmp_path / "read.pcap", READ)
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", f"1={good}", "-V"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert cli.returncode == 0, cli.stderr
    assert "        Register 0: 1 (0x0001)  A [x, \"y\"]\n" in cli.stdout
    assert "        Register 1: 10 (0x000A)  B [ab\"c]\n" in cli.stdout


@pytest.mark.parametrize("encoding, mark", [("utf-16-le", b"\xff\xfe"), ("utf-16-be", b"\xfe\xff")])
def test_a_utf16_map_says_what_to_save(tmp_path: Path, encoding: str, mark: bytes) -> None:
    saved = tmp_path / "map.txt"
    saved.write_bytes(mark + "address\tcode\tname\r\n1\tSPD\tMotor speed\r\n".encode(encoding))
    pcap = write_pcap(tmp_path / "read.pcap", READ)
    said = 'not UTF-8 text (UTF-16, as Excel\'s "Unicode Text" saves: save the map as "CSV UTF-8")'
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", f"1={saved}"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert (cli.returncode, cli.stdout, cli.stderr) == (2, "", f"vw3-decode: {saved}: {said}\n")
    _, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:1={saved}")
    assert any(text.endswith(f"{saved}: {said}") for _, text in record_experts), record_experts
