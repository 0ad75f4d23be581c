"""--report's noise events read as the rest of the product reads them: `1 byte of noise at offset 8`, never
`1 bytes`. The events' group row (render/report/groups.py) still groups every noise run whatever its
length (`1..2 bytes of noise at offset 15..48`), and reads singular only when each run of the group is one
byte (`1 byte of noise at offset 15..31`). Exact page rows and embedded data for exact bytes, from a file
and from standard input, under the compiled engine and the Python stages (VW3_PURE_PYTHON=1), which must
embed the same data."""
from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.pcapwriter import PcapWriter
from dissector.render.report.groups import EventGroups
from helpers import rtu, use_engine

T0 = 1767225600.0
QUESTION, ANSWER = rtu("01 03 0010 0001"), rtu("01 03 02 0007")


def records(noise: list[bytes]) -> list[tuple[bytes, float]]:
    """A read and its answer, then each noise run followed by another read and answer (10 ms apart)."""
    out = [(QUESTION, 0.0), (ANSWER, 0.010)]
    for index, run_bytes in enumerate(noise):
        at = 0.1 * (index + 1)
        out += [(run_bytes, at), (QUESTION, at + 0.020), (ANSWER, at + 0.030)]
    return out


def write(path: Path, noise: list[bytes]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for data, at in records(noise):
            writer.write(data, T0 + at)
    return path


def report(argv: list[str], page: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, stdin: bytes = b"") -> str:
    use_engine(monkeypatch, pure)
    out, err = io.StringIO(), io.StringIO()
    assert run([*argv, "-n", "--report", str(page)], Environment(io.BytesIO(stdin), out, err, False, False)) == 0
    assert err.getvalue() == ""
    return page.read_text(encoding="utf-8")


def pages(capture: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[str, dict]:
    """The page's events table and embedded data, asserted the same four ways (file/stdin x engine/pure)."""
    made = {}
    for where in ("file", "stdin"):
        for pure in (False, True):
            page = report([str(capture) if where == "file" else "-"], tmp_path / f"{where}{pure}.html",
                          monkeypatch, pure, capture.read_bytes() if where == "stdin" else b"")
            found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', page, re.S)
            assert found is not None
            table = re.search(r'<table class="events">.*?</table>', page, re.S)
            made[where, pure] = (table.group(0) if table else None, json.loads(found.group(1)))
    first = made["file", False]
    for way, got in made.items():
        assert got == first, way
    return first


def test_one_byte_runs_read_singular(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = write(tmp_path / "one.pcap", [b"\xaa", b"\xbb"])
    table, data = pages(capture, tmp_path, monkeypatch)
    assert [event for event in data["events"] if event[1] == "noise"] == [
        [0.1, "noise", None, "1 byte of noise at offset 15"],
        [0.2, "noise", None, "1 byte of noise at offset 31"],
    ]
    assert data["event_counts"]["noise"] == 2
    assert "<td>noise</td><td></td><td>1 byte of noise at offset 15..31</td><td>2</td>" in table
    assert "bytes of noise" not in table


def test_runs_of_one_and_more_bytes_are_one_group(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = write(tmp_path / "mixed.pcap", [b"\xaa", b"\xbb\xcc", b"\xdd"])
    table, data = pages(capture, tmp_path, monkeypatch)
    assert [event for event in data["events"] if event[1] == "noise"] == [
        [0.1, "noise", None, "1 byte of noise at offset 15"],
        [0.2, "noise", None, "2 bytes of noise at offset 31"],
        [0.3, "noise", None, "1 byte of noise at offset 48"],
    ]
    assert "<td>noise</td><td></td><td>1..2 bytes of noise at offset 15..48</td><td>3</td>" in table
    assert table.count("<td>noise</td>") == 1


def test_groups_join_singular_and_plural_texts() -> None:
    groups = EventGroups()
    groups.add("noise", None, "1 byte of noise at offset 8", 1.0, 2)
    groups.add("noise", None, "1 byte of noise at offset 30", 2.0, 5)
    (group,) = groups.rows()
    assert (group.label, group.count) == ("1 byte of noise at offset 8..30", 2)
    groups.add("noise", None, "4 bytes of noise at offset 60", 3.0, 9)
    (group,) = groups.rows()
    assert (group.label, group.count, group.first_frame, group.last_frame) == (
        "1..4 bytes of noise at offset 8..60", 3, 2, 9)
    groups = EventGroups()
    groups.add("noise", None, "4 bytes of noise at offset 0", 1.0, 1)
    groups.add("noise", None, "1 byte of noise at offset 9", 2.0, 3)
    (group,) = groups.rows()
    assert group.label == "1..4 bytes of noise at offset 0..9"
    groups = EventGroups()
    groups.add("crc", 1, "bad CRC, function 3, 8 bytes", 1.0, 1)
    (group,) = groups.rows()
    assert group.label == "bad CRC, function 3, 8 bytes"
