"""`--parquet`'s registers table has `words`, as --json's registers do: 2 on the first register of a 32-bit
map row read whole, 0 on its second, 1 on a 16-bit register (--json leaves it out then), null on a coil.
Read back by DuckDB and pyarrow, under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
from pathlib import Path

import duckdb
import pyarrow.parquet as pq
import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

# The SEL-749M with a user map: PWR int32 at 2..3, FREQ float32 (CDAB) at 4..5, IA 16-bit at 0.
MAP = """address;code;name;unit;scale;type;order
0;IA;Phase A current;A;0,1;;
2;PWR;Real power;kW;0,001;int32;ABCD
4;FREQ;Frequency;Hz;;float32;CDAB
"""
# A read of 0..5 (IA, 1, PWR, FREQ), then a coil read of 0..2 (bits: no words).
FRAMES = ["03 03 0000 0006", "03 03 0C 0064 0000 FFFF FF38 147B 4248", "03 01 0000 0003", "03 01 01 05"]
# (frame, address, value, words): every register and bit of the capture, as the table must hold them.
EXPECTED = [
    (2, 0, 100, 1), (2, 1, 0, 1), (2, 2, 65535, 2), (2, 3, 65336, 0), (2, 4, 5243, 2), (2, 5, 16968, 0),
    (4, 0, 1, None), (4, 1, 0, None), (4, 2, 1, None),
]


@pytest.fixture
def capture(tmp_path: Path) -> tuple[Path, Path]:
    table = tmp_path / "map.csv"
    table.write_text(MAP, encoding="utf-8")
    path = tmp_path / "sel.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(FRAMES):
            writer.write(rtu(frame), 1700000000 + index * 0.01)
    return table, path


@pytest.mark.parametrize("pure", [False, True])
def test_words_read_back(capture: tuple[Path, Path], tmp_path: Path, pure: bool,
                         monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    table, path = capture
    options = ["--profile", "sel749m", "--map", f"sel749m={table}", str(path)]
    status, out, err = run_cli(["--json", *options])
    assert (status, err) == (0, "")
    from_json = [(record["frame"], register["address"], register["value"], register.get("words", 1))
                 for record in map(json.loads, out.splitlines()) for register in record.get("registers") or []]
    assert from_json == EXPECTED[:6]  # (the JSON's words, as the table must say them)
    data = tmp_path / "data"
    status, out, err = run_cli(["--parquet", str(data), *options])
    assert (status, out, err) == (0, f"{path}: 4 frames, 9 registers, 0 events\n", "")
    rows = duckdb.connect().execute(
        f"SELECT frame, address, value, words FROM read_parquet('{data}/registers/*.parquet') "
        "ORDER BY frame, access, address").fetchall()
    assert rows == EXPECTED
    arrow = pq.read_table(str(data / "registers"))
    assert str(arrow.schema.field("words").type) == "int8"
    names = arrow.schema.names  # (added after text, as the columns added later: earlier positions kept)
    assert names[names.index("text") + 1 :] == ["words", "write", "exception_code"]
    assert arrow.column("words").to_pylist() == [row[3] for row in EXPECTED]
