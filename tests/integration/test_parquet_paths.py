"""--parquet and paths that are not UTF-8 (a file copied from an old Latin-1 share keeps its byte 0xE9):
pyarrow holds paths and the dataset's `file` column as UTF-8 strings, so such a capture or folder was a
UnicodeEncodeError traceback (hunt 58). Refused in one line, naming the path's bytes, exit 2, nothing written."""
from __future__ import annotations

import os
import shutil
import sys

import pytest

from conftest import ROOT
from helpers import run_cli

import pyarrow  # noqa: F401  (the test extra: missing, the test fails, never skips)
pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX byte file names")


def test_capture_name_not_utf8(tmp_path, monkeypatch):
    capture = os.path.join(os.fsdecode(bytes(tmp_path)), os.fsdecode(b"mesure\xe9.bin"))
    shutil.copy(ROOT / "captures" / "p38_protection.bin", capture)
    monkeypatch.chdir(tmp_path)
    status, out, err = run_cli(["--parquet", "data", os.fsdecode(b"mesure\xe9.bin")])
    assert (status, out) == (2, "")
    assert err == ("vw3-decode: mesure\\xe9.bin: its path is not UTF-8 text, which the dataset's file column"
                   " holds: rename it or decode it from a UTF-8 folder\n")
    assert not (tmp_path / "data").exists()


def test_folder_not_utf8(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = run_cli(["--parquet", os.fsdecode(b"donn\xe9es"), str(ROOT / "captures" / "p38_protection.bin")])
    assert (status, out) == (2, "")
    assert err == ("vw3-decode: --parquet donn\\xe9es: the folder's path is not UTF-8 text, which pyarrow"
                   " writes to: give another folder\n")
    assert os.listdir(tmp_path) == []
