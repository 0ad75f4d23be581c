"""Profile `auto` choosing the ATV71 for a slave after its FC4 reads (render/history.py _rehome): on the ATV71
FC4 reads the holding registers (atv71.toml input_registers "holding"), so the reads counted before the choice
are CHCF's, the parameter FC3 reads after it. --stats, --stats --json, --watch and --report show one CHCF, in
both engines, whether the choice comes in a later file (each file chosen over by a first pass) or later on
standard input (one pass). Before, the C engine and the Python stages kept an `input 8401` row beside CHCF
(10 reads, unnamed after a later file's choice), and --watch missed the change 3 -> 4."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, stats_section, use_engine

POLL = rtu("02 04 20D1 0001") + rtu("02 04 02 0003")  # generic: input register 8401 = 3
IDENT = rtu("02 2B 0E 01 00") + rtu(
    "02 2B 0E 01 02 00 00 02 00 0D" + b"Telemecanique".hex() + "01 0B" + b"ATV71HU15M3".hex())
CHCF = rtu("02 03 20D1 0001") + rtu("02 03 02 0004")  # the ATV71's CHCF = 4

ONE_CHCF = [
    "slave  address  code  reads  unreadable  writes  refused  last                    changes",
    "-----------------------------------------------------------------------------------------",
    "    2     8401  CHCF     13           0       0        0  4 (not a listed value)        1",
]


def _files(tmp_path: Path) -> list[str]:
    first, second = tmp_path / "polls.bin", tmp_path / "atv71.bin"
    first.write_bytes(POLL * 10)
    second.write_bytes(IDENT + CHCF * 3)
    return [str(first), str(second)]


@pytest.mark.parametrize("pure", [False, True])
def test_stats_one_chcf_after_a_later_files_choice(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", *_files(tmp_path)])
    assert status == 0, err
    assert stats_section(out) == ONE_CHCF


@pytest.mark.parametrize("pure", [False, True])
def test_stats_one_chcf_on_standard_input(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", "-"], stdin=POLL * 10 + IDENT + CHCF * 3)
    assert status == 0, err
    assert stats_section(out) == ONE_CHCF


@pytest.mark.parametrize("pure", [False, True])
def test_stats_json_one_holding_parameter(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", "--json", *_files(tmp_path)])
    assert status == 0, err
    assert json.loads(out)["parameters"] == [{
        "slave": 2, "address": 8401, "table": "holding", "code": "CHCF", "reads": 13, "unreadable": 0,
        "writes": 0, "refused": 0, "last": 4, "last_text": "4 (not a listed value)", "last_status": None,
        "changes": 1,
    }]


@pytest.mark.parametrize("pure", [False, True])
def test_watch_sees_the_change_across_the_choice(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--watch", "CHCF", *_files(tmp_path)])
    assert status == 0, err
    assert out.splitlines()[-1].split(None, 3)[2:] == ["2", "CHCF IO (I/O profile) -> 4 (not a listed value)"]


@pytest.mark.parametrize("pure", [False, True])
def test_report_one_series(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "bus.html"
    status, _out, err = run_cli(["--report", str(page), "-"], stdin=POLL * 10 + IDENT + CHCF * 3)
    assert status == 0, err
    html = page.read_text()
    assert "input 8401" not in html
    assert '"values":13,"marks":[],"marks_dropped":0,"x":[2.0,20.0,24.0,28.0],"y":[3,3,4,4]' in html


def test_both_tables_kept_join_in_both_stores() -> None:
    """A generic slave read at 8401 by FC3 and FC4, then found to be an ATV71: one parameter, its counts summed,
    the later state kept, a change where the two last states differ (the stories joined one after the other)."""
    from dissector.accel import _summary
    from dissector.render.stats_store import (
        HOLDING_REGISTERS, INPUT_REGISTERS, MAX_KEYS, READ, UNREADABLE, ParameterTable, parameter_rows, table_homes,
    )
    from dissector.devices.profiles import ONE_TABLE

    events = [
        (2, 8401, READ, 3, None, None, INPUT_REGISTERS),
        (2, 8401, READ, 5, None, None, HOLDING_REGISTERS),
        (2, 8401, READ, 3, None, None, INPUT_REGISTERS),
        (2, 8402, UNREADABLE, 0, None, "protected", INPUT_REGISTERS),  # moved alone: its status kept
        (2, 8403, READ, 7, None, None, INPUT_REGISTERS),
        (2, 8403, READ, 7, None, None, HOLDING_REGISTERS),  # the same value in both: no change
        (3, 8401, READ, 1, None, None, INPUT_REGISTERS),  # another slave's: stays
    ]
    stores = [_summary.Stats(MAX_KEYS), ParameterTable()]
    for store in stores:
        for event in events:
            store.param(*event)
        store.rehome(2, table_homes(ONE_TABLE))
        assert store.param(2, 8401, READ, 3, None, None, HOLDING_REGISTERS) is False  # 3 is its state now
    assert list(parameter_rows(stores[0])) == list(parameter_rows(stores[1])) == [
        (2, 8401, None, 4, 0, 0, 0, 3, None, 1, HOLDING_REGISTERS),
        (2, 8402, None, 0, 1, 0, 0, None, "protected", 0, HOLDING_REGISTERS),
        (2, 8403, None, 2, 0, 0, 0, 7, None, 0, HOLDING_REGISTERS),
        (3, 8401, None, 1, 0, 0, 0, 1, None, 0, INPUT_REGISTERS),
    ]
