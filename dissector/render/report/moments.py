"""The report's protection events, one a frame: the registers whose unreadable span a frame opened are
one event named by their span (`8401..8450 (50) protected or non-existent (exception 02)`, an exception
02 to a read of 50 ATV71 parameters, p.38) with each register in its detail, as the summary tells the
exception (`CHCF (8401) protected, COP (8402) protected, 8403..8412 non-existent (10), ...`); those it
made readable again are another. One register is told alone, as before (`CHCF (8401) protected`)."""
from __future__ import annotations

from typing import Any

Series = Any  # collect.py's Series (importing it here would be a cycle)


class Moments:
    """The protection moments of the frame at hand (key: its number, x and slave): the series whose span
    it opened (with status and how: ` (exception 02)`), those it closed."""

    __slots__ = ("key", "opened", "again")

    def __init__(self) -> None:
        self.key: tuple[int, float, int] | None = None
        self.opened: list[tuple[Series, str, str]] = []
        self.again: list[Series] = []

    def add(self, key: tuple[int, float, int], series: Series, status: str | None, how: str) -> None:
        self.key = key
        if status is None:
            self.again.append(series)
        else:
            self.opened.append((series, status, how))

    def take(self) -> list[tuple[Any, ...]]:
        """(number, x, slave, text, detail) of the frame's events, spans opened first; none left after."""
        if self.key is None:
            return []
        number, x, slave = self.key
        events = [(number, x, slave, *opened_text(self.opened))] if self.opened else []
        if self.again:
            events.append((number, x, slave, *again_text(self.again)))
        self.key, self.opened, self.again = None, [], []
        return events


def series_name(series: Series) -> str:
    shown = series.label or str(series.address)
    return f"{series.code} ({shown})" if series.code else shown


def _runs(entries: list[tuple[Series, str]]) -> list[tuple[Series, Series, str]]:
    """(first, last, status) of each run of consecutive addresses with one status and no code, a named
    register a run of its own."""
    runs: list[tuple[Series, Series, str]] = []
    for series, status in sorted(entries, key=lambda entry: entry[0].address):
        if runs and not series.code:
            first, last, was = runs[-1]
            if not last.code and was == status and series.address == last.address + 1:
                runs[-1] = (first, series, status)
                continue
        runs.append((series, series, status))
    return runs


def _span(series: list[Series]) -> str:
    """The registers of a frame's event: `8401..8450 (50)`, or its runs, `8400, 8405..8406 (3)`."""
    joined: list[list[Series]] = []
    for entry in sorted(series, key=lambda one: one.address):
        if joined and entry.address == joined[-1][1].address + 1:
            joined[-1][1] = entry
        else:
            joined.append([entry, entry])
    shown = [_shown(first) if first is last else f"{_shown(first)}..{_shown(last)}" for first, last in joined]
    return f"{', '.join(shown)} ({len(series)})"


def _shown(series: Series) -> str:
    return series.label or str(series.address)


def _detail(runs: list[tuple[Series, Series, str]]) -> str:
    """Each register of a frame's event, as the summary tells an exception's (`CHCF (8401) protected,
    8403..8412 non-existent (10)`)."""
    told = []
    for first, last, status in runs:
        after = f" {status}" if status else ""
        if first is last:
            told.append(f"{series_name(first)}{after}")
        else:
            told.append(f"{_shown(first)}..{_shown(last)}{after} ({last.address - first.address + 1})")
    return ", ".join(told)


def opened_text(opened: list[tuple[Series, str, str]]) -> tuple[str, str | None]:
    """The event of a frame's unreadable spans opened, and its detail (None: one register, told alone)."""
    how = opened[0][2]
    if len(opened) == 1:
        series, status, _how = opened[0]
        return f"{series_name(series)} {status}{how}", None
    statuses = " or ".join(dict.fromkeys(status for _series, status, _how in opened))
    return (f"{_span([series for series, _status, _how in opened])} {statuses}{how}",
            _detail(_runs([(series, status) for series, status, _how in opened])))


def again_text(again: list[Series]) -> tuple[str, str | None]:
    """The event of a frame's registers readable again, and its detail (None: one register)."""
    if len(again) == 1:
        return f"{series_name(again[0])} readable again", None
    return f"{_span(again)} readable again", _detail(_runs([(series, "") for series in again]))
