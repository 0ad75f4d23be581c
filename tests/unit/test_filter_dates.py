"""`-Y` compares `time` with a date and time in quotes, as tshark 4.0.17 compares frame.time
(render/filter_dates.py): ISO forms and tshark's `Jan  1, 2026 00:00:00.5`, local time unless a zone is
written. Before, `time >= "2026-01-01 00:00:00.5"` was refused ('time is a number, not ...'). The frames
each expression passes are tshark's, run on captures/p38_protection.pcap (times 2026-01-01 00:00:00.009115
UTC and on) with the plugin.
"""
from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from helpers import run_cli

CAPTURE = str(Path(__file__).resolve().parents[2] / "captures" / "p38_protection.pcap")
ALL = list(range(1, 13))


@pytest.fixture
def zone(monkeypatch: pytest.MonkeyPatch) -> Iterator[Callable[[str], None]]:
    """Run in the time zone TZ named (the process's own again after)."""
    def use(name: str) -> None:
        monkeypatch.setenv("TZ", name)
        time.tzset()

    yield use
    monkeypatch.undo()
    time.tzset()


def _frames(expression: str) -> list[int]:
    status, out, err = run_cli(["-T", "fields", "-e", "frame", "-Y", expression, CAPTURE])
    assert (status, err) == (0, "")
    return [int(line) for line in out.split()]


@pytest.mark.parametrize(("expression", "frames"), [
    ('time >= "2026-01-01 00:00:00.5"', ALL[2:]),
    ('time >= "2026-01-01T00:00:00.5"', ALL[2:]),
    ('time >= "Jan  1, 2026 00:00:00.5"', ALL[2:]),
    ('time >= "Jan 1, 2026 00:00:01"', ALL[4:]),
    ('time >= "2026-01-01 00:00:01Z"', ALL[4:]),
    ('time >= "2026-01-01 00:00:01 UTC"', ALL[4:]),
    ('time >= "Jan  1, 2026 00:00:00.5 UTC"', ALL[2:]),
    ('time >= "2026-01-01"', ALL),
    ('time >= "2026-01-01 00:00"', ALL),
    ('time >= "2026-01-01 00:00:00.5+01:00"', ALL),  # 23:00:00.5 the day before, in UTC
    ('time == "2026-01-01 00:00:00.009115"', [1]),  # exact to the microsecond the pcap holds
    ('time < "2026-01-01 00:00:00.5"', [1, 2]),
    ('time in {"2026-01-01 00:00:00.5".."2026-01-01 00:00:01.1"}', [3, 4, 5, 6]),
])
def test_dates_pass_what_tshark_passes(expression: str, frames: list[int],
                                       zone: Callable[[str], None]) -> None:
    zone("UTC")
    assert _frames(expression) == frames


def test_a_date_without_a_zone_is_local_time(zone: Callable[[str], None]) -> None:
    zone("Europe/Paris")  # UTC+1 in January
    assert _frames('time >= "2026-01-01 01:00:01"') == ALL[4:]
    assert _frames('time >= "2026-01-01 00:00:01Z"') == ALL[4:]


@pytest.mark.parametrize("text", ['"garbage"', '"2026-13-01 00:00:00"', '"Foo  1, 2026"', '"2026-02-30"'])
def test_no_date_is_one_error(text: str) -> None:
    status, out, err = run_cli(["-Y", f"time >= {text}", CAPTURE])
    assert (status, out) == (2, "")
    assert err == (f'vw3-decode: {text} is no date and time: write "2026-12-05 10:00:00" or "Dec  5, 2026 '
                   '10:00:00.5" (local time; Z, UTC or +01:00 for another zone) (column 9)\n'
                   f"  time >= {text}\n          ^\n")


def test_tsharks_field_name_is_named() -> None:
    status, _out, err = run_cli(["-Y", 'frame.time >= "2026-01-01"', CAPTURE])
    assert status == 2
    assert err.splitlines()[0] == ("vw3-decode: unknown field 'frame.time': only fields.KEY names a key "
                                   "inside a value (vw3-decode names it time) (column 1)")
