"""Dumps in 16-bit words (hunt 58): `hexdump cap.bin` (its default) and `od -x` were refused as "'0000000' is
an odd number of hex digits", and `od -A x -x` (six-digit offsets) was read as a one-frame-a-line hex dump:
offsets as bytes, each word's two bytes swapped (a little-endian machine writes 0c 03 as 030c), exit 0.
The text cannot say the byte order: refused in one line naming the dumps that give bytes."""
from __future__ import annotations

import pytest

from conftest import ROOT
from helpers import run_cli

# `hexdump p38_protection.bin | head -2` and `od -A x -x` of the same bytes (little-endian machine)
DUMPS = ["0000000 030c d020 0300 ef0e 030c 8006 0000 0003\n0000010 1702 0ce4 2003 00d0 0e03 0cef 0603 0080\n",
         "000000 030c d020 0300 ef0e 030c 8006 0000 0003\n000010 1702 0ce4 2003 00d0 0e03 0cef 0603 0080\n"]


@pytest.mark.parametrize("dump", DUMPS, ids=["hexdump", "od-A-x-x"])
def test_word_dump_is_refused(tmp_path, dump):
    (tmp_path / "d.txt").write_text(dump)
    assert run_cli([str(tmp_path / "d.txt")]) == (2, "", (
        f"vw3-decode: {tmp_path}/d.txt line 1: a dump in 16-bit words (hexdump's default, od -x), whose byte"
        " order is the dumping machine's: dump the bytes with hexdump -C, od -t x1 or xxd\n"))


def test_byte_dumps_still_read(tmp_path):
    (tmp_path / "d.txt").write_text("000000 0c 03 20 d0 00 03 0e ef\n000008\n")
    assert run_cli(["-T", "fields", "-e", "raw", str(tmp_path / "d.txt")]) == (0, "0c0320d000030eef\n", "")
