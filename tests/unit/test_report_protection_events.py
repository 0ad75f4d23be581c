"""--report tells a frame's protection moments as one event: an ATV71 exception 02 to a read of 8401..8450
(p.38) was 50 `protection` rows of the events table, 50 on the timeline, `protection: 50`; now one,
named by its span with each register in its detail, as the summary tells the exception. The registers a
frame makes readable again are one event too; one register alone is told as before (atv.pcap-like pages
unchanged); the trend marks stay one a register. Exact page text for exact bytes, the file and standard
input, under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

T0 = 1700000000.0
VALUES = " ".join(f"{value:04X}" for value in range(1, 51))
FRAMES = [
    (0.0, "0C 03 20D0 0003"), (0.02, "0C 03 06 8000 0003 8000"),  # 8400 non-existent, COP protected (p.38)
    (1.0, "0C 03 20D1 0032"), (1.02, "0C 83 02"),  # exception 02 to 8401..8450: all unreadable (COP already)
    (2.0, "0C 03 20D1 0032"), (2.02, "0C 83 02"),  # the same again: no state changes
    (3.0, "0C 03 20D1 0032"), (3.02, f"0C 03 64 {VALUES}"),  # 8401..8450 readable again
]
EVENTS = (
    '<table class="events"><thead><tr><th>kind</th><th>slave</th><th>event</th><th>count</th><th>first</th>'
    "<th>last</th></tr></thead><tbody>"
    "<tr><td>protection</td><td>12</td><td><details><summary>8400, 8402 (2) non-existent or protected</summary>"
    "8400 non-existent, COP (8402) protected</details></td><td>1</td><td>0.020000 #2</td><td></td></tr>"
    "<tr><td>exception</td><td>12</td><td>exception 02 to function 3: address does not exist (also: every parameter "
    "read is non-existent or protected)</td><td>2</td><td>1.020000 #4</td><td>2.020000 #6</td></tr>"
    "<tr><td>protection</td><td>12</td><td><details><summary>8401, 8403..8450 (49) protected or non-existent "
    "(exception 02)</summary>CHCF (8401) protected, 8403..8412 non-existent (10), FR1 (8413) protected, 8414..8422 "
    "non-existent (9), CD1 (8423) protected, 8424..8450 non-existent (27)</details></td><td>1</td>"
    "<td>1.020000 #4</td><td></td></tr>"
    "<tr><td>protection</td><td>12</td><td><details><summary>8401..8450 (50) readable again</summary>CHCF (8401), "
    "COP (8402), 8403..8412 (10), FR1 (8413), 8414..8422 (9), CD1 (8423), 8424..8450 (27)</details></td><td>1</td>"
    "<td>3.020000 #8</td><td></td></tr></tbody></table>"
)
PROTECTIONS = [
    [0.02, "protection", 12, "8400, 8402 (2) non-existent or protected", "8400 non-existent, COP (8402) protected"],
    [1.02, "protection", 12, "8401, 8403..8450 (49) protected or non-existent (exception 02)",
     "CHCF (8401) protected, 8403..8412 non-existent (10), FR1 (8413) protected, 8414..8422 non-existent (9), "
     "CD1 (8423) protected, 8424..8450 non-existent (27)"],
    [3.02, "protection", 12, "8401..8450 (50) readable again",
     "CHCF (8401), COP (8402), 8403..8412 (10), FR1 (8413), 8414..8422 (9), CD1 (8423), 8424..8450 (27)"],
]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    path = tmp_path / "p38.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for offset, frame in FRAMES:
            writer.write(rtu(frame), T0 + offset)
    return path


def _page(argv: list[str], page: Path, stdin: bytes = b"") -> tuple[str, dict]:
    status, out, err = run_cli(["--profile", "atv71", "--report", str(page), *argv], stdin=stdin)
    assert (status, out, err) == (0, "", "")
    text = page.read_text("utf-8")
    return text, json.loads(re.search(r'id="report-data">(.*?)</script>', text, re.S).group(1))


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("stdin", [False, True])
def test_one_event_a_frame(capture: Path, tmp_path: Path, pure: bool, stdin: bool,
                           monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    argv, data = (["-"], capture.read_bytes()) if stdin else ([str(capture)], b"")
    text, page = _page(argv, tmp_path / "r.html", data)
    assert re.search(r'<table class="events">.*?</table>', text).group(0) == EVENTS
    assert "<p>exception: 2, protection: 3, crc: 0, noise: 0, silence: 0, unanswered: 0</p>" in text
    assert [event for event in page["events"] if event[1] == "protection"] == PROTECTIONS
    assert page["event_counts"]["protection"] == 3
    timeline = [column for column in page["event_columns"] if column["kind"] == "protection"]
    assert timeline == [{"kind": "protection", "x": [0.016, 1.016, 3.016], "n": [1, 1, 1]}]
    # The trends keep one row and one mark a register: 8400..8450, each span opened and closed.
    parameters = {parameter["address"]: parameter["marks"] for parameter in page["parameters"]}
    assert sorted(parameters) == list(range(8400, 8451))
    assert parameters[8400] == [[0.02, "non-existent"]]
    assert parameters[8402] == [[0.02, "protected"], [3.02, "readable again (protected before)"]]
    assert parameters[8450] == [[1.02, "non-existent (exception 02)"], [3.02, "readable again (non-existent before)"]]
    assert sum(len(marks) for marks in parameters.values()) == 101


@pytest.mark.parametrize("pure", [False, True])
def test_one_register_is_told_alone(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """An exception 02 to 8401 alone: `CHCF (8401) protected (exception 02)`, no detail (as before)."""
    use_engine(monkeypatch, pure)
    path = tmp_path / "one.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for offset, frame in [(0.0, "0C 03 20D1 0001"), (0.02, "0C 83 02")]:
            writer.write(rtu(frame), T0 + offset)
    text, page = _page([str(path)], tmp_path / "r.html")
    assert [event for event in page["events"] if event[1] == "protection"] == [
        [0.02, "protection", 12, "CHCF (8401) protected (exception 02)"]]
    assert ("<tr><td>protection</td><td>12</td><td>CHCF (8401) protected (exception 02)</td><td>1</td>"
            "<td>0.020000 #2</td><td></td></tr>") in text
