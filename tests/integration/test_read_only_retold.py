"""--report re-tells an exception decoded before profile `auto` chose its slave's device (standard input)
with the meaning explain_exception gives it once chosen (report/collect.py _retell): an exception 02 refusing
a write of read-only parameters means the refusal (data/modbus.toml read_only_meaning), as the file's page
says. Before, the retold event said the code's plain meaning ('address does not exist'). Compiled engine and
VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import ROOT
from test_read_only_meaning import ATV71, MEANING


@pytest.mark.parametrize("pure", [False, True])
def test_the_report_retells_a_refusal_told_before_auto_chose(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                             pure: bool) -> None:
    # ATV71's frames as slave 2 first (nothing known of it yet, standard input: provisional), then the card's
    # identification, which makes auto choose the ATV71: the page's events as the file's.
    use_engine(monkeypatch, pure)
    data = b"".join(rtu("02" + frame[2:]) for frame in ATV71)
    data += (ROOT / "captures" / "atv71_commissioning.bin").read_bytes()
    events = []
    for source, stdin in (([str(tmp_path / "auto.bin")], b""), (["-"], data)):
        (tmp_path / "auto.bin").write_bytes(data)
        page = tmp_path / "auto.html"
        assert run_cli([*source, "--profile", "auto", "-q", "--report", str(page)], stdin=stdin)[0] == 0
        text = page.read_text(encoding="utf-8")
        found = json.loads(re.search(r'id="report-data">(.*?)</script>', text).group(1))  # type: ignore[union-attr]
        events.append([event[3] for event in found["events"] if event[1] == "exception"][:3])
    assert events == [[f"exception 02 to function 6: {MEANING}", f"exception 02 to function 16: {MEANING}",
                       "exception 02 to function 6: address does not exist"]] * 2
