"""--parquet's list columns (frames' `warnings`, `notes`, `comments`) are [] when a row has none, on every row kind:
a noise run's `notes` was null (its --json record has no `notes` key) while a frame's was []. Read back
with pyarrow: the exact rows for exact bytes, engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import glob
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# Noise, ATV71 reads of CHCF (8401): 3, then a request with a bad CRC, the read again and exception 02; an
# FC43 request with read code 5 (a warning) the capture ends after (not known whether it was answered);
# glitch bytes at the end (noise).
READ = rtu("0C 03 20 D1 00 01")
DATA = (bytes.fromhex("00fffff0") + READ + rtu("0C 03 02 00 03") + READ[:-1] + b"\x00" + READ + rtu("0C 83 02")
        + rtu("01 2B 0E 05 00") + bytes.fromhex("fee0"))
PROTECTED = ["exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
             "CHCF (8401) protected", "CHCF (8401) became protected: read 3 in frame #3, exception 02 now"]
CODE5 = "read device id code 5 outside the spec's 1..4 (a server answers exception 03)"


@BOTH
def test_list_columns_are_empty_lists_not_null(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = tmp_path / "bus.bin"
    capture.write_bytes(DATA)
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), "--profile", "atv71", str(capture)])
    assert (status, out, err) == (0, f"{capture}: 8 frames, 2 registers, 5 events\n", "")
    (path,) = glob.glob(str(tmp_path / "data" / "frames" / "*.parquet"))
    table = pq.read_table(path)
    lists = [field.name for field in table.schema if pa.types.is_list(field.type)]
    assert lists == ["warnings", "notes", "comments"]
    assert pq.read_table(path, columns=["comments"]).column(0).to_pylist() == [[]] * 8  # (no packet comment)
    rows = table.select(["frame", "kind", "crc_ok", "warnings", "notes"]).to_pylist()
    assert [tuple(row.values()) for row in rows] == [
        (1, "noise", None, [], []),
        (2, "request", True, [], []),
        (3, "response", True, [], []),
        (4, "request", False, [], []),
        (5, "request", True, [], []),
        (6, "exception", True, [], PROTECTED),
        (7, "request", True, [CODE5], ["the capture ends before any response: not known whether it was answered"]),
        (8, "noise", None, [], []),
    ]
    for name in ("registers", "events"):  # no list column there: nothing to be null or []
        (path,) = glob.glob(str(tmp_path / "data" / name / "*.parquet"))
        assert not [field.name for field in pq.read_schema(path) if pa.types.is_list(field.type)]
