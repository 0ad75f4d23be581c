"""A Mask Write (FC22) its echo confirms, on a slave without a device profile (no parameter memory), gives
its register the value the spec's rule makes of the last value --stats knows, (old AND and_mask) OR
(or_mask AND NOT and_mask) (Application Protocol 6.16; history.History._mask, the store's `last`), in
--stats, --stats --json, --watch and --report, the compiled engine (_stats.h count_transaction) as the
Python stages. Before, with no re-read after it, --stats kept the stale pre-write value as `last` (18 for
a register the write made 23, the spec's own example)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, stats_section, use_engine, write_rtu

# 8402 read 18 (0x12), masked AND 00F2 OR 0025 (the spec's example: 23), not read again; 8404 masked with
# nothing known of it (stays empty); 8406 read 16#8000 under no profile: a value (32768), masked to 0x8005.
FRAMES = [
    "0C 03 20D2 0001", "0C 03 02 0012",
    "0C 16 20D2 00F2 0025", "0C 16 20D2 00F2 0025",
    "0C 16 20D4 00F2 0025", "0C 16 20D4 00F2 0025",
    "0C 03 20D6 0001", "0C 03 02 8000",
    "0C 16 20D6 FFF0 0005", "0C 16 20D6 FFF0 0005",
]
EXPECTED = [
    "slave   address  code  reads  unreadable  writes  refused  last   changes",
    "-------------------------------------------------------------------------",
    "   12      8402            1           0       1        0  23           1",
    "   12      8404            0           0       1        0               0",
    "   12      8406            1           0       1        0  32773        1",
    "  all  3 params            2           0       3        0               2",
]


def _capture(tmp_path: Path) -> Path:
    return write_rtu(tmp_path / "mask.bin", FRAMES)


@pytest.mark.parametrize("pure", [False, True])
def test_stats_last_is_the_masked_value(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats"])
    assert status == 0, err
    assert stats_section(out) == EXPECTED


@pytest.mark.parametrize("pure", [False, True])
def test_json_stats_last_is_the_masked_value(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--json"])
    assert status == 0, err
    rows = json.loads(out)["parameters"]
    assert [(row["address"], row["writes"], row["last"], row["changes"]) for row in rows] == [
        (8402, 1, 23, 1), (8404, 1, None, 0), (8406, 1, 32773, 1)]


@pytest.mark.parametrize("pure", [False, True])
def test_watch_and_report_show_the_masked_value(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--watch", "8402,8404"])
    assert status == 0, err
    assert out.splitlines() == ["     4            -  12 8402 18 -> 23"]
    page = tmp_path / "report.html"
    status, _out, err = run_cli([str(_capture(tmp_path)), "--report", str(page)])
    assert status == 0, err
    data = json.loads(page.read_text().split('id="report-data">', 1)[1].split("</script>", 1)[0])
    points = {row["address"]: row["y"] for row in data["parameters"]}
    assert points[8402] == [18, 23]
