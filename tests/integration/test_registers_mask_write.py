"""A Mask Write (FC22) is a register written: `-T registers` and `--parquet`'s registers table show its
request's row (`write`) and its echo's (`echo`) at the register's address, the masks in `text` as the
summary shows them, what became of it in `write` as for FC6 (confirmed, differs, refused, broadcast,
unanswered), and a `value` only where it is known (and_mask 0: or_mask), byte for byte under the compiled
engine and VW3_PURE_PYTHON=1. Frames 1-2 as pymodbus 3.16.1 answered mbpoll on a pty (2026-12-06)."""
from __future__ import annotations

from pathlib import Path

import duckdb
import pytest

from helpers import engine_output_as_python, rtu, run_cli, write_rtu

BUS = [
    "01 16 0028 00F2 0025", "01 16 0028 00F2 0025",  # pymodbus echoes: confirmed, the value not known
    "01 16 0028 0000 0025", "01 16 0028 0000 0025",  # and_mask 0: the register holds or_mask, 37
    "01 16 0028 FFFF 0025", "01 16 0028 00F2 0025",  # the echo's masks are not the request's: differs
    "01 16 0029 00F2 0025", "01 96 02",  # refused, exception 02
    "00 16 0028 00F2 0025",  # a broadcast: no answer comes
]
UNKNOWN = ": the result depends on the value before"
LINES = [
    "frame,time,slave,function,access,address,label,code,name,value,scaled,unit,status,text,write,exception_code",
    f"1,,1,22,write,40,,,,,,,,AND 0x00F2 OR 0x0025{UNKNOWN},confirmed,",
    f"2,,1,22,echo,40,,,,,,,,AND 0x00F2 OR 0x0025{UNKNOWN},confirmed,",
    "3,,1,22,write,40,,,,37,,,,AND 0x0000 OR 0x0025,confirmed,",
    "4,,1,22,echo,40,,,,37,,,,AND 0x0000 OR 0x0025,confirmed,",
    f"5,,1,22,write,40,,,,,,,,AND 0xFFFF OR 0x0025{UNKNOWN},differs,",
    f"6,,1,22,echo,40,,,,,,,,AND 0x00F2 OR 0x0025{UNKNOWN},confirmed,",
    f"7,,1,22,write,41,,,,,,,,AND 0x00F2 OR 0x0025{UNKNOWN},refused,2",
    f"9,,0,22,write,40,,,,,,,,AND 0x00F2 OR 0x0025{UNKNOWN},broadcast,",
]


def test_mask_write_rows(monkeypatch: pytest.MonkeyPatch) -> None:
    argv = ["-T", "registers", "-E", "header=y", "-E", "separator=,"] + [
        arg for frame in BUS for arg in ("--hex", rtu(frame).hex())]
    out, _framed = engine_output_as_python(argv, monkeypatch)
    assert out.splitlines() == LINES


def test_unanswered_mask_write(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python(
        ["-T", "registers", "--hex", rtu("01 16 0028 00F2 0025").hex(), "--hex", rtu("01 03 0000 0001").hex()],
        monkeypatch)
    assert out.split("\t")[14] == "unanswered"


def test_parquet_has_the_same_rows(tmp_path: Path) -> None:
    capture = write_rtu(tmp_path / "bus.bin", BUS)
    status, _out, err = run_cli(["--parquet", str(tmp_path / "data"), str(capture)])
    assert (status, err) == (0, "")
    rows = duckdb.connect().execute(
        "SELECT frame, access, address, value, text, write, exception_code, words "
        f"FROM read_parquet('{tmp_path}/data/registers/*.parquet')").fetchall()
    expected = []
    for line in LINES[1:]:
        cells = line.split(",")
        expected.append((int(cells[0]), cells[4], int(cells[5]), int(cells[9]) if cells[9] else None, cells[13],
                         cells[14], int(cells[15]) if cells[15] else None, 1))
    assert rows == expected
