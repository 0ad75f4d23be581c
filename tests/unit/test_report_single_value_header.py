"""--report's table of parameters with a single value: its last columns count the reads and the writes of
that one value as --stats counts them (a column headed "values" holding 2 read as two values in a table of
single values; one headed "readings" counted writes too: a parameter only written showed `readings 1`
where --stats says reads 0, writes 1)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

HEADER = "<th>slave</th><th>address</th><th>code</th><th>name</th><th>value</th><th>reads</th><th>writes</th>"


def _table(tmp_path: Path, data: bytes) -> str:
    capture = tmp_path / "capture.bin"
    capture.write_bytes(data)
    page = tmp_path / "page.html"
    code, _, err = run_cli(["--profile", "atv71", "--report", str(page), str(capture)])
    assert code == 0, err
    html = page.read_text()
    return re.search(r'Parameters with a single value</h3><table class="single">(.*?)</table>', html).group(1)


@pytest.mark.parametrize("pure", [False, True])
def test_single_value_table_counts_reads(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    # ATV71 (slave 12): CHCF (8401) read twice, the same value both times
    table = _table(tmp_path, rtu("0C03 20D1 0001") + rtu("0C03 02 0003") + rtu("0C03 20D1 0001") + rtu("0C03 02 0003"))
    assert HEADER in table
    assert "<td>12</td><td>8401</td><td>CHCF</td><td>Profile</td><td>IO (I/O profile)</td><td>2</td><td>0</td>" in table


@pytest.mark.parametrize("pure", [False, True])
def test_single_value_table_counts_writes_apart(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    # CHCF written once (FC6 and its echo), COP (8402) read once: as --stats, reads 0 writes 1 and reads 1 writes 0
    data = rtu("0C06 20D1 0003") + rtu("0C06 20D1 0003") + rtu("0C03 20D2 0001") + rtu("0C03 02 0005")
    table = _table(tmp_path, data)
    assert HEADER in table
    assert ("<td>12</td><td>8401</td><td>CHCF</td><td>Profile</td><td>IO (I/O profile)</td><td>0</td><td>1</td>"
            in table)
    assert "<td>12</td><td>8402</td><td>COP</td><td>Copy channel 1 &lt;&gt; 2</td><td>5 (not a listed value)</td>" \
           "<td>1</td><td>0</td>" in table
    capture = tmp_path / "capture.bin"
    code, out, _ = run_cli(["--profile", "atv71", "--stats", str(capture)])
    assert code == 0
    assert re.search(r"\n +12 +8401 +CHCF +0 +0 +1 +0 ", out)
