"""Input registers and holding registers are two tables (Modbus Application Protocol 4.3): input register 5
(FC4) and holding register 5 (FC3, FC6, FC16, FC22, FC23) are two parameters in --watch, --stats and
--report (render/history.py keys parameters by slave, table and address; profiles.register_table takes
the table from data/modbus.toml [plc_references]: FC4's registers are 3X). Before, one parameter held both,
and a poll of the two read as changes that never happened: `--watch 5` printed `17 5 1 -> 2`, `2 -> 1`,
... and --stats one row, reads 6, changes 6. The compiled engine (dissector/accel/_stats.h, _report.h)
gives the same output as VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, stats_section, use_engine, write_rtu

# Slave 17 polls holding register 5 (1) and input register 5 (2) twice, then reads 7 and 8, then writes
# holding register 5 = 9 (FC6, echoed).
FRAMES = [
    "11 03 0005 0001", "11 03 02 0001", "11 04 0005 0001", "11 04 02 0002",
    "11 03 0005 0001", "11 03 02 0001", "11 04 0005 0001", "11 04 02 0002",
    "11 03 0005 0001", "11 03 02 0007", "11 04 0005 0001", "11 04 02 0008",
    "11 06 0005 0009", "11 06 0005 0009",
]


def _capture(tmp_path: Path) -> Path:
    return write_rtu(tmp_path / "tables.bin", FRAMES)


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("style", "expected"), [
    ([], ["    10            -  17 5 1 -> 7", "    12            -  17 input 5 2 -> 8", "    14            -  17 5 7 -> 9"]),
    (["--address-style", "plc"],
     ["    10            -  17 40006 1 -> 7", "    12            -  17 30006 2 -> 8", "    14            -  17 40006 7 -> 9"]),
])
def test_watch_follows_each_table(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, style: list[str],
                                  expected: list[str]) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--watch", "5", *style])
    assert status == 0, err
    assert out.splitlines() == expected


@pytest.mark.parametrize("pure", [False, True])
def test_watch_json_names_the_input_register(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--watch", "5", "--json"])
    assert status == 0, err
    changes = [json.loads(line) for line in out.splitlines()]
    assert [(change["frame"], change["old"], change["new"], change.get("label")) for change in changes] == [
        (10, "1", "7", None), (12, "2", "8", "input 5"), (14, "7", "9", None)]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("style", "holding", "inputs"), [([], "      5", "input 5"),
                                                          (["--address-style", "plc"], "  40006", "  30006")])
def test_stats_counts_each_table_apart(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                       style: list[str], holding: str, inputs: str) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", *style])
    assert status == 0, err
    assert stats_section(out) == [
        "slave   address  code  reads  unreadable  writes  refused  last  changes",
        "------------------------------------------------------------------------",
        f"   17   {holding}            3           0       1        0  9           2",
        f"   17   {inputs}            3           0       0        0  8           1",
        "  all  2 params            6           0       1        0              3",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_stats_json_says_the_table(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--json", "--address-style", "plc"])
    assert status == 0, err
    rows = json.loads(out)["parameters"]
    assert [(row["address"], row["table"], row["label"], row["reads"], row["writes"], row["last"], row["changes"])
            for row in rows] == [(5, "holding", "40006", 3, 1, 9, 2), (5, "input", "30006", 3, 0, 8, 1)]


@pytest.mark.parametrize("pure", [False, True])
def test_report_draws_each_table(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "report.html"
    status, _out, err = run_cli([str(_capture(tmp_path)), "--report", str(page)])
    assert status == 0, err
    data = json.loads(page.read_text().split('id="report-data">', 1)[1].split("</script>", 1)[0])
    assert [(row["address"], row["table"], row["label"], row["x"], row["y"]) for row in data["parameters"]] == [
        (5, "holding", None, [2.0, 6.0, 10.0, 14.0], [1, 1, 7, 9]),
        (5, "input", "input 5", [4.0, 8.0, 12.0], [2, 2, 8]),
    ]
    assert data["written"] == ["17:5"]


def test_both_stores_keep_the_tables_apart() -> None:
    """The compiled store (_stats.h param_key) and ParameterTable: the same rows, by slave, address and table;
    a run of neighbouring addresses is one table's."""
    from dissector.accel import _summary
    from dissector.render.stats_store import (
        HOLDING_REGISTERS, INPUT_REGISTERS, MAX_KEYS, READ, ParameterTable, parameter_rows,
    )

    compiled, python = _summary.Stats(MAX_KEYS), ParameterTable()
    events = [(1, address, READ, 7, None, None, table) for address in (5, 6, 7, 8)
              for table in (HOLDING_REGISTERS, INPUT_REGISTERS)] + [(1, 6, READ, 9, None, None, INPUT_REGISTERS)]
    assert [compiled.param(*event) for event in events] == [python.param(*event) for event in events]
    assert list(parameter_rows(compiled)) == python.parameters()
    assert [(row[1], row[10], row[7], row[9]) for row in python.parameters()] == [
        (5, 0, 7, 0), (5, 1, 7, 0), (6, 0, 7, 0), (6, 1, 9, 1), (7, 0, 7, 0), (7, 1, 7, 0), (8, 0, 7, 0), (8, 1, 7, 0)]
    pieces = python.table(60, 3)[0]
    assert compiled.table(60, 3) == python.table(60, 3)
    # (A run is of rows next to each other: the two tables' rows alternate here, each is its own.)
    assert [[(row[1], row[10]) for row in piece] for piece in pieces] == [
        [(5, 0)], [(5, 1)], [(6, 0)], [(6, 1)], [(7, 0)], [(7, 1)], [(8, 0)], [(8, 1)]]
