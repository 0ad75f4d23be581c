"""`od -t x1` dumps (hunt 58), the dump every Unix has: `od -A x -t x1 capture.bin > d.txt` was read as a
one-frame-a-line hex dump, each line's offset taken for bytes (`000010` -> 00 00 10 in the stream): frames
garbled silently ('Read Holding Registers 1664 (0)', 'CRC BAD'). Its offsets (hex with -A x, octal by
default, decimal with -A d; a `*` for repeats; -t x1z's >...< column) place the bytes as xxd's do."""
from __future__ import annotations

import shutil
import subprocess

import pytest

from conftest import ROOT
from helpers import run_cli

P38 = ROOT / "captures" / "p38_protection.bin"
# `od -A x -t x1 p38_protection.bin | head -3`, as GNU od 8.32 prints it
OD_HEX = """\
000000 0c 03 20 d0 00 03 0e ef 0c 03 06 80 00 00 03 00
000010 02 17 e4 0c 03 20 d0 00 03 0e ef 0c 03 06 80 00
000020 00 03 00 02 17 e4
000026
"""
KEYS = ["-T", "fields", "-e", "frame", "-e", "kind", "-e", "raw"]
FOUR = "1\trequest\t0c0320d000030eef\n2\tresponse\t0c030680000003000217e4\n" \
       "3\trequest\t0c0320d000030eef\n4\tresponse\t0c030680000003000217e4\n"


def test_od_hex_offsets(tmp_path):
    (tmp_path / "d.txt").write_text(OD_HEX)
    assert run_cli([*KEYS, str(tmp_path / "d.txt")]) == (0, FOUR, "")


def test_od_octal_and_decimal_offsets(tmp_path):
    rows = [line.split(" ", 1)[1] if " " in line else "" for line in OD_HEX.splitlines()]
    for offsets in (["0000000", "0000020", "0000040", "0000046"], ["0000000", "0000016", "0000032", "0000038"]):
        text = "".join(f"{offset} {row}".rstrip() + "\n" for offset, row in zip(offsets, rows))
        (tmp_path / "d.txt").write_text(text)
        assert run_cli([*KEYS, str(tmp_path / "d.txt")]) == (0, FOUR, ""), text


def test_a_line_missing(tmp_path):
    lines = OD_HEX.splitlines(keepends=True)
    (tmp_path / "d.txt").write_text(lines[0] + lines[2] + lines[3])
    status, out, err = run_cli([str(tmp_path / "d.txt")])
    assert (status, out) == (2, "")
    assert err == (f"vw3-decode: {tmp_path}/d.txt line 2: offset 000020 does not follow the 16 bytes before (bytes"
                   " missing or repeated)\n")


@pytest.mark.skipif(shutil.which("od") is None, reason="needs od")
@pytest.mark.parametrize("options", [["-A", "x", "-t", "x1"], ["-t", "x1"], ["-A", "d", "-t", "x1"],
                                     ["-A", "x", "-t", "x1z"], ["-A", "o", "-t", "x1", "-w8"]])
def test_real_od_gives_the_capture(tmp_path, options):
    """Every od layout, on a capture with a squeezed run of zeros first and inside (od's `*`)."""
    capture = tmp_path / "z.bin"
    data = P38.read_bytes()
    capture.write_bytes(b"\0" * 100 + data[:19] + b"\0" * 64 + data[19:])
    (tmp_path / "d.txt").write_text(subprocess.run(["od", *options, str(capture)], capture_output=True, text=True,
                                                   check=True).stdout)
    assert run_cli([*KEYS, str(tmp_path / "d.txt")]) == run_cli([*KEYS, str(capture)])
