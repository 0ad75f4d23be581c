"""--report's table of parameters with a single value: its last column counts the readings of that one value
(a column headed "values" holding 2 read as two values in a table of single values)."""
from __future__ import annotations

import re
from pathlib import Path

from helpers import rtu, run_cli


def test_single_value_table_counts_readings(tmp_path: Path) -> None:
    # ATV71 (slave 12): CHCF (8401) read twice, the same value both times
    capture = tmp_path / "twice.bin"
    capture.write_bytes(rtu("0C03 20D1 0001") + rtu("0C03 02 0003") + rtu("0C03 20D1 0001") + rtu("0C03 02 0003"))
    page = tmp_path / "page.html"
    code, _, err = run_cli(["--profile", "atv71", "--report", str(page), str(capture)])
    assert code == 0, err
    html = page.read_text()
    table = re.search(r'Parameters with a single value</h3><table class="single">(.*?)</table>', html).group(1)
    assert "<th>slave</th><th>address</th><th>code</th><th>name</th><th>value</th><th>readings</th>" in table
    assert re.search(r"<td>12</td><td>8401</td><td>CHCF</td><td>[^<]*</td><td>[^<]*</td><td>2</td>", table)
