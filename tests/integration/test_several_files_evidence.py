"""Several files read as one bus (`vw3-decode --stats a.bin b.bin`) number their frames each from 1, as the
summary shows them under each `==> FILE <==`: the evidence --stats and --watch cite names the file with the
frame number, so a user finds the frame. Before, profile `auto`'s reason said `in frame #2` (the second
file's frame 2, the first file's frame 2 being an FC4 read) and --watch's line said frame 4 with no file.
Compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
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
        "     4            -   2 CHCF 3 IO (I/O profile) -> 4 (not a listed value)",
        "==> polls.bin <==",
        "     2            -   2 CHCF 4 (not a listed value) -> 3 IO (I/O profile)",
    ]
    status, out, err = run_cli(["--watch", "CHCF", "--json", *files])
    assert [(change["frame"], change["file"]) for change in map(json.loads, out.splitlines())] == [(4, "atv71.bin")]
