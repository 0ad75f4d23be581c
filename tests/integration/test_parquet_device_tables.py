"""--parquet's protection events follow the slave's device's tables, as the summary's notes do: on the ATV71
(profile input_registers "holding") FC4's 16#8000 at 8401 and FC3's next read of it are one parameter, CHCF,
so the read is a `readable-again` event (the summary says "CHCF (8401) readable again: protected in frame
#2"); before, parquet keyed the events by the code's table alone and told nothing at frame 4."""
from __future__ import annotations

from pathlib import Path

import duckdb

from helpers import run_cli, write_rtu


def test_atv71_fc4_then_fc3_is_one_parameter(tmp_path: Path) -> None:
    capture = write_rtu(tmp_path / "atv71.bin", ["01 04 20D1 0002", "01 04 04 8000 0000",
                                                "01 03 20D1 0001", "01 03 02 0001"])
    status, _out, err = run_cli([str(capture), "--profile", "atv71", "--parquet", str(tmp_path / "data")])
    assert status == 0, err
    events = duckdb.connect().execute(
        f"SELECT kind, frame, address, code, status FROM read_parquet('{tmp_path}/data/events/*.parquet') "
        "WHERE kind IN ('protected', 'readable-again') ORDER BY frame").fetchall()
    assert events == [("protected", 2, 8401, "CHCF", "protected"), ("readable-again", 4, 8401, "CHCF", "ok")]
