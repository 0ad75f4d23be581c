"""File names that are not UTF-8 (a byte 0xff in a name from an old Latin-1 system): Python gives them as
lone surrogates (PEP 383); every title, message and output shows each such byte as \\xNN, the form the
tool escapes control characters in. Before, messages and titles said `a\\udcffb.bin` (a character the name
does not hold), and --report stopped with a UnicodeEncodeError traceback. tshark prints the raw byte."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
POLL = rtu("01 03 0000 0001") + rtu("01 03 02 0007")
NAME = os.fsdecode(b"a\xffb.bin")  # 'a\udcffb.bin'


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    monkeypatch.chdir(tmp_path)
    Path(NAME).write_bytes(POLL)
    Path("ok.bin").write_bytes(POLL)
    return [NAME, "ok.bin"]


@BOTH
def test_titles_and_records_name_the_byte(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(files)
    assert (status, err) == (0, "")
    assert [line for line in out.splitlines() if line.startswith("==>")] == ["==> a\\xffb.bin <==", "==> ok.bin <=="]
    status, out, err = run_cli(["--json", *files])
    assert (status, err) == (0, "")
    assert json.loads(out.splitlines()[0])["file"] == "a\\xffb.bin"
    status, out, err = run_cli(["-T", "fields", "-e", "file", "-e", "frame", *files])
    assert out.splitlines()[:2] == ["a\\xffb.bin\t1", "a\\xffb.bin\t2"]


def test_messages_name_the_byte(files: list[str]) -> None:
    missing = os.fsdecode(b"x\xffy.bin")
    assert run_cli([missing]) == (2, "", "vw3-decode: x\\xffy.bin: no such file\n")
    status, _out, err = run_cli(["--map", os.fsdecode(b"m\xff.csv"), files[1]])
    assert status == 2 and err.startswith("vw3-decode: m\\xff.csv: cannot read the map"), err


def test_report_of_such_a_file(files: list[str]) -> None:
    report = Path(os.fsdecode(b"r\xff.html"))
    status, _out, err = run_cli(["--report", str(report), *files])
    assert (status, err) == (0, "")
    assert "vw3-decode report: a\\xffb.bin, ok.bin" in report.read_text()
