"""--report and --watch of standard input where profile `auto` takes slave 247 for an ATV71 (whose FC4 reads its
holding registers) at its FC6 answer and takes that back at an FC2 answer (frame #6): the FC4 read counted while
it was an ATV71 (3201..3203) is an input register again, as --stats says and the file (named with the last
choice, `generic`, throughout) draws and watches it. The listeners moved what they kept by the register's table
(render/watch.py rehomed, report/reading.py rehome), which a choice taken back leaves as it is: from standard
input frame by frame the report kept 3201..3203 as holding registers and --watch lost the change 1591 -> 1592.
They move by the protocol tables of the codes that set their states (Series.origins, told by the engine too:
dissector/accel/_report.h, which forgets a slave's trends when its device changes; Watcher._origins)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import fed_piece_by_piece

from dissector.accel import fastsummary

# FC4 3201..3203, FC6 8501 := 15 (echoed), FC2 (which the VW3 A3 303 does not support), FC4 3201..3203 again
FRAMES = [bytes.fromhex(f) for f in (
    "f7040c810003f7e5", "f70406063700000000ba95", "f7062135000fc76a", "f7062135000fc76a",
    "f70220d10022b77c", "f7020585f1c72fb5be64", "f7040c810003f7e5", "f704060638000100023e95",
)]
WAYS = ["file", "at-once", "frame-by-frame"]


def vw3_decode(args: list[str], pure: bool, way: str, tmp_path: Path) -> str:
    source = "-"
    if way == "file":
        source = str(tmp_path / "bus.bin")
        Path(source).write_bytes(b"".join(FRAMES))
    return fed_piece_by_piece([*args, source], {"file": [], "at-once": [b"".join(FRAMES)]}.get(way, FRAMES), pure)


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("way", WAYS)
def test_report_draws_the_input_registers(tmp_path: Path, pure: bool, way: str) -> None:
    page = tmp_path / "bus.html"
    vw3_decode(["--report", str(page)], pure, way, tmp_path)
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', page.read_text(), re.S)
    assert found is not None
    drawn = [(p["table"], p["address"], p["label"], p["values"], p["x"], p["y"])
             for p in json.loads(found.group(1))["parameters"]]
    assert drawn == [
        ("input", 3201, "input 3201", 2, [2.0, 8.0], [1591, 1592]),
        ("input", 3202, "input 3202", 2, [2.0, 8.0], [0, 1]),
        ("input", 3203, "input 3203", 2, [2.0, 8.0], [0, 2]),
        ("holding", 8501, None, 1, [4.0], [15]),
    ]


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("way", WAYS)
def test_watch_sees_the_input_registers_change(tmp_path: Path, pure: bool, way: str) -> None:
    # (read once, the frames after the choice taken back are provisional until the slave's choice settles)
    mark = "" if way == "file" else " [provisional]"
    assert vw3_decode(["--watch", "3201,3202,8501"], pure, way, tmp_path).splitlines() == [
        f"     8            - 247 input 3201 1591 -> 1592{mark}",
        f"     8            - 247 input 3202 0 -> 1{mark}",
    ]
