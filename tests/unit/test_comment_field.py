"""A pcapng packet comment is the key `comment` of -Y and -T fields, as tshark 4.0's frame.comment (one
occurrence per comment, FT_STRING): `-Y 'comment contains "pump"'`, `-T fields -e comment`. Before, -Y
comment was "unknown field" and -e comment "not a field"; only -V and --json showed comments (d93720e).
tshark 4.0.17 on the same records: frame.comment selects the commented frames, len(frame.comment) > 10 the
long one, upper(frame.comment) contains "PUMP" and frame.comment matches "^pump" frame 7 of noisy_bus."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from test_pcapng_comments import ANSWER, COMMENTED, REQUEST, _write

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def _selected(path: Path, expression: str) -> list[str]:
    status, out, _err = run_cli(["-Y", expression, "-T", "fields", "-e", "frame", "-e", "comment", str(path)])
    assert status == 0
    return out.splitlines()


@BOTH
@pytest.mark.parametrize(("expression", "expected"), [
    ("comment", ["1\tpoll \\x1b[31m of 12", "2\tanswer,again", "3\tglitch"]),
    ("!comment", []),
    ('comment == "again"', ["2\tanswer,again"]),  # (some occurrence)
    ('comment contains "poll"', ["1\tpoll \\x1b[31m of 12"]),
    ('comment matches "^GL"', ["3\tglitch"]),  # (case-insensitive, as Wireshark's)
    ("count(comment) == 2", ["2\tanswer,again"]),
    ("len(comment) > 6", ["1\tpoll \\x1b[31m of 12"]),
    ('upper(comment) == "ANSWER"', ["2\tanswer,again"]),
    ('comment != "answer"', ["1\tpoll \\x1b[31m of 12", "3\tglitch"]),  # (all_ne: none is)
])
def test_the_filter_takes_comments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                   expression: str, expected: list[str]) -> None:
    use_engine(monkeypatch, pure)
    assert _selected(_write(tmp_path, COMMENTED), expression) == expected


@BOTH
def test_fields_writes_comments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, [(0, REQUEST, []), (10_000, ANSWER, ["answer", "again"])])
    status, out, _err = run_cli(["-T", "fields", "-e", "frame", "-e", "comment", "-E", "occurrence=l", str(path)])
    assert (status, out.splitlines()) == (0, ["1\t", "2\tagain"])


def test_frame_comment_is_named() -> None:
    status, _out, err = run_cli(["-Y", "frame.comment", "-c", "1", "--hex", "0C 03 20 D0 00 03"])
    assert status == 2
    assert err.splitlines()[0] == ("vw3-decode: unknown field 'frame.comment': only fields.KEY names a key "
                                   "inside a value (vw3-decode names it comment) (column 1)")
