"""A Mask Write (FC22) its echo confirms is a write of its register in --stats, --watch and --report, as an
FC6 write of the value it gives the register (history.History._mask): the writes count one, and where the
parameter memory knows the value (memory.remember_mask; and_mask 0: or_mask, whatever the device) the
parameter's last value is it and its change is the echo's, as FC6's; where it does not, the write is
counted and the last value stays as it was (as for a write nothing confirmed). An exception to it counts as
refused. Before, none of the three counted anything of an FC22. The compiled engine hands every FC22
transaction to the Python stages, and gives the same output as VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, stats_section, use_engine, write_rtu

# COP (8402) read 18, masked AND 00F2 OR 0025 (the spec's example: 23), read 23; 8403 masked AND 0000 OR
# 0005 (5 whatever it held); 8404 masked while nothing is known of it; 8405's mask refused (exception 01).
FRAMES = [
    "0C 03 20D2 0001", "0C 03 02 0012",
    "0C 16 20D2 00F2 0025", "0C 16 20D2 00F2 0025",
    "0C 03 20D2 0001", "0C 03 02 0017",
    "0C 16 20D3 0000 0005", "0C 16 20D3 0000 0005",
    "0C 16 20D4 00F2 0025", "0C 16 20D4 00F2 0025",
    "0C 16 20D5 00F2 0025", "0C 96 01",
]
HEADER = [
    "slave   address  code  reads  unreadable  writes  refused  last                     changes",
    "-------------------------------------------------------------------------------------------",
]
TRACKED = HEADER + [
    "   12      8402  COP       2           0       1        0  23 (not a listed value)        1",
    "   12      8403            0           0       1        0  5                              0",
    "   12      8404            0           0       1        0                                 0",
    "   12      8405            0           0       1        1                                 0",
    "  all  4 params            2           0       4        1                                 1",
]
# No profile (generic: no parameter memory): only a mask with and_mask 0 gives a known value.
UNTRACKED = [
    "slave   address  code  reads  unreadable  writes  refused  last  changes",
    "------------------------------------------------------------------------",
    "   12      8402            2           0       1        0  23          1",
    "   12      8403            0           0       1        0  5           0",
    "   12      8404            0           0       1        0              0",
    "   12      8405            0           0       1        1              0",
    "  all  4 params            2           0       4        1              1",
]


def _capture(tmp_path: Path) -> Path:
    return write_rtu(tmp_path / "mask.bin", FRAMES)


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("profile", "expected"), [(["--profile", "atv71"], TRACKED), ([], UNTRACKED)])
def test_stats_count_a_mask_write_as_a_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                             profile: list[str], expected: list[str]) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), *profile, "--stats"])
    assert status == 0, err
    assert stats_section(out) == expected


@pytest.mark.parametrize("pure", [False, True])
def test_the_json_stats_row_of_a_masked_parameter(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--profile", "atv71", "--stats", "--json"])
    assert status == 0, err
    rows = json.loads(out)["parameters"]
    assert rows[0] == {"slave": 12, "address": 8402, "table": "holding", "code": "COP", "reads": 2, "unreadable": 0,
                       "writes": 1, "refused": 0, "last": 23, "last_text": "23 (not a listed value)",
                       "last_status": None, "changes": 1}
    assert [(row["address"], row["writes"], row["refused"], row["last"]) for row in rows[1:]] == [
        (8403, 1, 0, 5), (8404, 1, 0, None), (8405, 1, 1, None)]


@pytest.mark.parametrize("pure", [False, True])
def test_watch_shows_the_change_at_the_echo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--profile", "atv71", "--watch", "COP,8403"])
    assert status == 0, err
    assert out.splitlines() == [
        "     4            -  12 COP 18 (not a listed value) -> 23 (not a listed value)",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_the_report_draws_the_masked_value_as_a_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                      pure: bool) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "report.html"
    status, _out, err = run_cli([str(_capture(tmp_path)), "--profile", "atv71", "--report", str(page)])
    assert status == 0, err
    text = page.read_text()
    data = json.loads(text.split('id="report-data">', 1)[1].split("</script>", 1)[0])
    assert data["written"] == ["12:8402", "12:8403"]
    points = {row["address"]: (row["x"], row["y"]) for row in data["parameters"]}
    assert points == {8402: ([2.0, 4.0, 6.0], [18, 23, 23]), 8403: ([8.0], [5])}
