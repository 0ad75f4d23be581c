"""`-T registers` says per row what became of a write (columns `write` and `exception_code`), as the
Parquet registers table does, byte for byte under the compiled engine and VW3_PURE_PYTHON=1: the mbpoll
session of test_write_outcomes (a real master refused by a pymodbus slave on a pty), then a header and
exact lines."""
from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest

from helpers import engine_output_as_python
from test_write_outcomes import WRITES, write_capture


def rows(out: str) -> list[tuple]:
    """(frame, access, address, value, write, exception_code) of each write's row, typed as WRITES."""
    found = []
    for row in csv.reader(io.StringIO(out), delimiter="\t"):
        if row[4] != "read":
            found.append((int(row[0]), row[4], int(row[5]), int(row[9]), row[14], int(row[15]) if row[15] else None))
    return found


def test_refused_unanswered_and_confirmed_writes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = str(write_capture(tmp_path / "mbpoll.pcap"))
    out, _framed = engine_output_as_python(["-T", "registers", capture], monkeypatch)
    assert rows(out) == WRITES
    out, _framed = engine_output_as_python(["-T", "registers", "--timeout", "0.2", capture], monkeypatch)
    assert [row for row in rows(out) if row[0] in (15, 16)] == [(15, "write", 20, 77, "unanswered", None),
                                                               (16, "echo", 20, 78, "confirmed", None)]
    out, _framed = engine_output_as_python(
        ["-T", "registers", "-E", "header=y", "-E", "separator=,", "-Y", "frame in {3, 5}", capture], monkeypatch)
    # (the capture is a nanosecond pcap: its time column at 9 decimals, as tshark -T fields shows it)
    assert out.splitlines() == [
        "frame,time,slave,function,access,address,label,code,name,value,scaled,unit,status,text,write,exception_code",
        "3,0.035982000,1,6,write,100,,,,5,,,,,refused,2",
        "5,0.068061000,1,16,write,199,,,,5,,,,,refused,2",
        "5,0.068061000,1,16,write,200,,,,6,,,,,refused,2",
    ]
