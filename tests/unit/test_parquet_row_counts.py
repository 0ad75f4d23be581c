"""--parquet's line per capture counts each table's rows with its noun singular for one: `1 frame, 1
register, 0 events`, never `1 frames` (export/parquet.py rows_text; the line written by app/jobs.py: patch
/work/patches/hunt68-parquet-plural.diff)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli

from dissector.export.parquet import rows_text

pytest.importorskip("pyarrow")


def test_one_frame_one_register(tmp_path: Path) -> None:
    capture = tmp_path / "one.bin"
    capture.write_bytes(rtu("01 06 0005 0007"))  # a write of 5 = 7, unanswered: one frame, one register
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), str(capture)])
    assert (status, out, err) == (0, f"{capture}: 1 frame, 1 register, 0 events\n", "")


@pytest.mark.parametrize(("rows", "text"), [
    ((1, 1, 1), "1 frame, 1 register, 1 event"),
    ((0, 0, 0), "0 frames, 0 registers, 0 events"),
    ((12, 18, 5), "12 frames, 18 registers, 5 events"),
])
def test_rows_text(rows: tuple[int, int, int], text: str) -> None:
    assert rows_text(dict(zip(("frames", "registers", "events"), rows))) == text
