"""--report re-tells an exception decoded before profile `auto` chose its slave's device (standard input,
one pass) with the meaning the device gives it, and that meaning is the one the file's page gives: to a
read, p.38's clause too. The retold event lacked it ("exception 02 to function 3: address does not exist")
where the file said "... (also: every parameter read is non-existent or protected)". Exact event text,
the file and standard input, under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

# p.38's exception first (nothing known of slave 12 yet), then the page's reads, which make auto choose ATV71
# (CHCF becoming protected).
FRAMES = ["0C 03 20D0 0003", "0C 83 02"] + [
    "0C 03 20D0 0003", "0C 03 06 8000 0003 0002", "0C 03 20D0 0003", "0C 03 06 8000 0003 0002",
    "0C 03 20D0 0003", "0C 03 06 8000 8000 0002", "0C 03 20D0 0003", "0C 03 06 8000 8000 0002",
]
READ_EVENT = ("exception 02 to function 3: address does not exist (also: every parameter read is "
              "non-existent or protected)")


def _exception_events(page: str) -> list[str]:
    return re.findall(r"<td>(exception [0-9A-F]{2} to function \d+[^<]*)</td>", page)


@pytest.mark.parametrize("pure", [False, True])
def test_an_exception_told_before_auto_chose_gets_the_read_clause(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                   pure: bool) -> None:
    use_engine(monkeypatch, pure)
    data = b"".join(rtu(frame) for frame in FRAMES)
    capture = tmp_path / "exception_first.bin"
    capture.write_bytes(data)
    from_file, from_stdin = tmp_path / "file.html", tmp_path / "stdin.html"
    status, _out, err = run_cli([str(capture), "--report", str(from_file)])
    assert status == 0, err
    status, _out, err = run_cli(["-", "--report", str(from_stdin)], stdin=data)
    assert status == 0, err
    file_events = _exception_events(from_file.read_text())
    assert READ_EVENT in file_events
    assert _exception_events(from_stdin.read_text()) == file_events
