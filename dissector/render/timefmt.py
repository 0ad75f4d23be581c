"""The time column, in tshark's `-t` formats.

Reference points come from the capture, never from what the display filter lets through: relative
time (`r`) counts from the first item of the input and `d` from the item captured just before, as
tshark does; only `dd` (delta displayed) looks at what was shown.
"""
from __future__ import annotations

import time as _time
from dataclasses import dataclass, field

from dissector.model import Item

# -t value -> what tshark calls it (for --help and error messages)
TIME_FORMATS: dict[str, str] = {
    "r": "relative to the first item",
    "a": "local time of day",
    "ad": "local date and time",
    "d": "delta from the previous item captured",
    "dd": "delta from the previous item displayed",
    "e": "seconds since the epoch",
    "u": "UTC time of day",
    "ud": "UTC date and time",
}
UNTIMED = "-"
# Keys -T fields takes besides the NDJSON ones (tshark's frame.time_relative, time_delta, ..._displayed).
TIME_FIELDS = ("time_relative", "time_delta", "time_delta_displayed")


# What tshark's time column says of a time the platform's calendar cannot hold. The readers refuse
# such records (sources/common.py TIME_RANGE, issue 32); a library caller's own times may still be.
NOT_REPRESENTABLE = "Not representable"


def whole_micros(seconds: float) -> tuple[int, int]:
    """(whole seconds, microseconds) of a time: from a Stamp's integer nanoseconds where it has them (a
    float of year 1 is -6.2e10 s, which keeps 8 us at best: .005000 showed .004997), else the float's."""
    ns = getattr(seconds, "ns", None)
    if ns is not None:
        whole, rest = divmod(ns, 1_000_000_000)
        micros = round(rest / 1000)
    else:
        whole = int(seconds // 1)
        micros = round((seconds - whole) * 1_000_000)
    if micros == 1_000_000:  # 0.9999996 rounds up into the next second
        whole, micros = whole + 1, 0
    return whole, micros


def _clock_text(seconds: float, utc: bool, date: bool) -> str:
    whole, micros = whole_micros(seconds)
    try:
        parts = _time.gmtime(whole) if utc else _time.localtime(whole)
        day = f"{parts.tm_year:04d}-{parts.tm_mon:02d}-{parts.tm_mday:02d} " if date else ""  # 0001, as tshark
        return f"{day}{_time.strftime('%H:%M:%S', parts)}.{micros:06d}"
    except (OverflowError, OSError, ValueError):  # outside time_t or the C library's years
        return NOT_REPRESENTABLE


@dataclass(slots=True)
class Clock:
    """Turns item times into the text of the time column; one per input (times restart per input)."""

    format: str = "r"
    deltas: bool = False  # keep each item's previous captured time even when -t is not d (-e time_delta)
    first: float | None = None  # time of the first timed item captured
    _previous_captured: float | None = None
    _previous_shown: float | None = None
    _before: dict[int, float | None] = field(default_factory=dict)  # id(item) -> previous captured time

    def reset(self) -> None:
        self.first = self._previous_captured = self._previous_shown = None
        self._before.clear()

    def observe(self, items: list[Item]) -> None:
        """See items as captured, before any display filter (call for every item, in order)."""
        track = self.deltas or self.format == "d"
        for item in items:
            time = item.time
            if time is None:
                continue
            if self.first is None:
                self.first = time
            if track:
                self._before[id(item)] = self._previous_captured
            self._previous_captured = time

    def text(self, item: Item) -> str:
        """The column for an item being shown (call in display order)."""
        time = item.time
        if time is None:
            return UNTIMED
        fmt = self.format
        if fmt == "r":
            return f"{time - (self.first if self.first is not None else time):.6f}"
        if fmt == "d":
            previous = self._before.pop(id(item), None)
            return f"{time - previous:.6f}" if previous is not None else "0.000000"
        if fmt == "dd":
            previous, self._previous_shown = self._previous_shown, time
            return f"{time - previous:.6f}" if previous is not None else "0.000000"
        if fmt == "e":
            return f"{time:.6f}"
        return _clock_text(time, utc=fmt.startswith("u"), date=fmt.endswith("d"))

    def seconds(self, item: Item, key: str) -> str | None:
        """TIME_FIELDS values for an item being shown, 9 decimals as tshark prints them (call in
        display order)."""
        time = item.time
        if time is None:
            return None
        if key == "time_relative":
            reference = self.first
        elif key == "time_delta":
            reference = self._before.pop(id(item), None)
        else:
            reference, self._previous_shown = self._previous_shown, time
        return f"{0.0 if reference is None else time - reference:.9f}"

    def keep(self, items: list[Item]) -> None:
        """Only `items` of those observed will be shown (the rest were filtered out or cut by -c)."""
        before = self._before
        if before:
            self._before = {id(item): before[id(item)] for item in items if id(item) in before}
