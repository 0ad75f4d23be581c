"""Several files read as one bus (`vw3-decode --stats a.bin b.bin`) number their frames each from 1, as the
summary shows them under each `==> FILE <==`: the evidence --stats and --watch cite names the file with the
frame number, so a user finds the frame. Before, profile `auto`'s reason said `in frame #2` (the second
file's frame 2, the first file's frame 2 being an FC4 read) and --watch's line said frame 4 with no file.
Compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, stats_section, use_engine

POLL = rtu("02 04 20D1 0001") + rtu("02 04 02 0003")
IDENT = rtu("02 2B 0E 01 00") + rtu(
    "02 2B 0E 01 02 00 00 02 00 0D" + b"Telemecanique".hex() + "01 0B" + b"ATV71HU15M3".hex())
CHCF = rtu("02 03 20D1 0001") + rtu("02 03 02 0004")
REASON = "Read Device Identification in frame #2 of atv71.bin: ProductCode 'ATV71HU15M3'"


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "polls.bin").write_bytes(POLL * 10)
    (tmp_path / "atv71.bin").write_bytes(IDENT + CHCF * 3)
    return ["polls.bin", "atv71.bin"]


@pytest.mark.parametrize("pure", [False, True])
def test_stats_reason_names_the_file(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", *files])
    assert status == 0, err
    assert stats_section(out, "Device profiles") == [
        "slave  profile  why",
        "-" * 94,
        f"    2  atv71    {REASON}",
    ]
    status, out, err = run_cli(["--stats", "--json", *files])
    assert json.loads(out)["profiles"] == [
        {"slave": 2, "profile": "atv71", "reason": REASON, "frame": 2, "file": "atv71.bin"}]


def test_one_file_cites_the_number_alone(files: list[str]) -> None:
    status, out, _err = run_cli(["--stats", "atv71.bin"])
    assert stats_section(out, "Device profiles")[2] == (
        "    2  atv71    Read Device Identification in frame #2: ProductCode 'ATV71HU15M3'")


@pytest.mark.parametrize("pure", [False, True])
def test_watch_lines_under_their_file(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--watch", "CHCF", *files, "polls.bin"])
    assert status == 0, err
    assert out.splitlines() == [
        "==> atv71.bin <==",
        "     4            -   2 CHCF IO (I/O profile) -> 4 (not a listed value)",
        "==> polls.bin <==",
        "     2            -   2 CHCF 4 (not a listed value) -> IO (I/O profile)",
    ]
    status, out, err = run_cli(["--watch", "CHCF", "--json", *files])
    assert [(change["frame"], change["file"]) for change in map(json.loads, out.splitlines())] == [(4, "atv71.bin")]


def _page(argv: list[str], page: Path) -> tuple[dict, str]:
    status, _out, err = run_cli([*argv, "--report", str(page)])
    assert status == 0, err
    text = page.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', text, re.S)
    assert found is not None
    return json.loads(found.group(1)), text


@pytest.mark.parametrize("pure", [False, True])
def test_report_numbers_on_and_cites_by_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """Two untimed files, an exception in frame 4 of each: the report's x axis numbers the second file's frames
    on (5..8), so its points and events are not drawn over the first's (or dropped as going back), and the
    events table cites each by its file, as the summary numbers it."""
    use_engine(monkeypatch, pure)
    monkeypatch.chdir(tmp_path)
    for name, value, address in (("a.bin", "0003", "9999"), ("b.bin", "0004", "9998")):
        (tmp_path / name).write_bytes(rtu("0C 03 20D1 0001") + rtu(f"0C 03 02 {value}")
                                      + rtu(f"0C 03 {address} 0001") + rtu("0C 83 02"))
    data, text = _page(["a.bin", "b.bin"], tmp_path / "bus.html")
    assert data["inputs"] == [[0, "a.bin"], [4, "b.bin"]]
    assert [event[:2] for event in data["events"]] == [[4.0, "exception"], [8.0, "exception"]]
    assert [(entry["x"], entry["y"]) for entry in data["parameters"]] == [([2.0, 6.0], [3, 4])]
    assert ("<td>exception</td><td>12</td><td>exception 02 to function 3</td><td>2</td>"
            "<td>#4 of a.bin</td><td>#4 of b.bin</td>") in text
    single, text = _page(["a.bin"], tmp_path / "one.html")
    assert "inputs" not in single and "<td>#4</td>" in text


@pytest.mark.parametrize("pure", [False, True])
def test_report_one_chcf_over_the_files(files: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                        pure: bool) -> None:
    use_engine(monkeypatch, pure)
    data, text = _page(files, tmp_path / "bus.html")
    assert "input 8401" not in text
    assert [(entry["code"], entry["x"], entry["y"]) for entry in data["parameters"]] == [
        ("CHCF", [2.0, 20.0, 24.0, 28.0], [3, 3, 4, 4])]


@pytest.mark.parametrize("pure", [False, True])
def test_memory_cites_a_frame_of_the_file_before(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """CHCF read 3 in a.bin's frame 2, then 16#8000 in b.bin's frame 2: the summary under b.bin said "read 3 in
    frame #2", which is b.bin's own frame; now the frame of the file before is cited with it (memory.cite_from),
    one of the same file by its number alone."""
    use_engine(monkeypatch, pure)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.bin").write_bytes(rtu("0C 03 20D1 0002") + rtu("0C 03 04 0003 0002"))
    (tmp_path / "b.bin").write_bytes(rtu("0C 03 20D1 0002") + rtu("0C 03 04 8000 0002"))
    (tmp_path / "c.bin").write_bytes(rtu("0C 03 20D1 0001") + rtu("0C 03 02 0003")
                                     + rtu("0C 03 20D1 0002") + rtu("0C 03 04 8000 0002"))
    status, out, err = run_cli(["--profile", "atv71", "a.bin", "b.bin"])
    assert status == 0, err
    assert out.splitlines()[-1] == (
        "     2            -  12 response  Read Holding Registers 8401..8402 (2): CHCF=protected COP=Cd (command) [#1] "
        "[CHCF (8401) became protected: read 3 in frame #2 of a.bin, 16#8000 now]  CRC ok")
    status, out, err = run_cli(["--profile", "atv71", "a.bin", "c.bin"])
    assert out.splitlines()[-1].endswith("[CHCF (8401) became protected: read 3 in frame #2, 16#8000 now]  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_report_empty_and_noise_files_between(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """An empty file and a file of line noise between two: the noise run is the noise file's frame 1, the
    second exception b.bin's frame 4 (numbered on: x 9), and the empty file takes no number."""
    use_engine(monkeypatch, pure)
    monkeypatch.chdir(tmp_path)
    for name, address in (("a.bin", "9999"), ("b.bin", "9998")):
        (tmp_path / name).write_bytes(rtu("0C 03 20D1 0001") + rtu("0C 03 02 0003")
                                      + rtu(f"0C 03 {address} 0001") + rtu("0C 83 02"))
    (tmp_path / "empty.bin").write_bytes(b"")
    (tmp_path / "noise.bin").write_bytes(b"\xff" * 300)
    data, text = _page(["a.bin", "empty.bin", "noise.bin", "b.bin"], tmp_path / "bus.html")
    assert data["inputs"] == [[0, "a.bin"], [4, "empty.bin"], [4, "noise.bin"], [5, "b.bin"]]
    assert [event[:2] for event in data["events"]] == [[4.0, "exception"], [5.0, "noise"], [9.0, "exception"]]
    assert "<td>#4 of a.bin</td><td>#4 of b.bin</td>" in text
    assert "<td>300 bytes of noise at offset 0</td><td>1</td><td>#1 of noise.bin</td>" in text
