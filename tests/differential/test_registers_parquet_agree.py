"""`-T registers` and `--parquet`'s registers table are the same rows (render/registers.py register_rows),
what became of each write included (`write`, `exception_code`), on random buses with damaged frames: the
compiled engine and VW3_PURE_PYTHON=1 print the same lines (engine_output_as_python), and DuckDB reads those
rows back from the Parquet file."""
from __future__ import annotations

import csv
import io
import random
from collections import Counter
from pathlib import Path

import duckdb
import pytest

from helpers import engine_output_as_python, rtu, run_cli
from test_timed_summary import cut_records, frames_of, write_pcap

COLUMNS = "frame, slave, function, access, address, value, status, write, exception_code"
# Writes refused (the random bus answers its writes normally or not at all) and an echo of another value.
REFUSALS = ["01 06 0064 0005", "01 86 02", "07 10 00C7 0002 04 0005 0006", "07 90 03",
            "0C 17 0001 0002 0010 0001 02 0009", "0C 97 01", "01 06 0014 004D", "01 06 0014 004E"]


def _cell(text: str) -> int | str | None:
    return None if text == "" else int(text) if text.lstrip("-").isdigit() else text


@pytest.mark.parametrize("seed", range(2))
def test_registers_lines_are_the_parquet_rows(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "bus.pcap"
    frames = frames_of(seed + 200, damaged=0.06)
    end = frames[-1][1] + 100_000_000
    frames += [(rtu(frame), end + index * 20_000_000) for index, frame in enumerate(REFUSALS)]
    write_pcap(capture, cut_records(random.Random(seed), frames, "frame"))
    out, _framed = engine_output_as_python(["-T", "registers", "-E", "header=y", str(capture)], monkeypatch)
    lines = list(csv.DictReader(io.StringIO(out), delimiter="\t"))
    shown = [tuple(_cell(line[key]) for key in COLUMNS.split(", ")) for line in lines]
    status, _out, err = run_cli(["--parquet", str(tmp_path / "data"), str(capture)])
    assert (status, err) == (0, "")
    # (no ORDER BY: the file's order, which is the lines': frames in order, registers then bits)
    table = f"read_parquet('{tmp_path}/data/registers/*.parquet')"
    rows = duckdb.connect().execute(f"SELECT {COLUMNS} FROM {table}").fetchall()
    assert rows == shown
    outcomes = Counter(row[7] for row in rows if row[3] == "write")
    assert {"confirmed", "refused", "unanswered", "unknown", "broadcast", "differs"} <= set(outcomes), outcomes
    assert [row[-2:] for row in rows if row[7] == "refused"][-4:] == [("refused", 2), ("refused", 3), ("refused", 3),
                                                                     ("refused", 1)]
