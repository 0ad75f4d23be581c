"""The time column, in tshark's `-t` formats.

Reference points come from the capture, never from what the display filter lets through: relative
time (`r`) counts from the first item of the input and `d` from the item captured just before, as
tshark does (a network, RTAC or several-interface capture's: from its packets, Clock.packets); only `dd`
(delta displayed) looks at what was shown.
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field
from typing import Any
from datetime import datetime, timezone

from dissector.model import Item, Stamp
from dissector.render.pcapwriter import NANOS, finer_than_micros

# -t value -> what tshark calls it (for --help and error messages)
TIME_FORMATS: dict[str, str] = {
    "r": "relative to the first item (a network, RTAC or several-interface capture: its first packet)",
    "a": "local time of day",
    "ad": "local date and time",
    "adoy": "local year/day of the year and time",
    "d": "delta from the previous item captured (a network, RTAC or several-interface capture: the packet before)",
    "dd": "delta from the previous item displayed",
    "e": "seconds since the epoch",
    "u": "UTC time of day",
    "ud": "UTC date and time",
    "udoy": "UTC year/day of the year and time",
}
UNTIMED = "-"
# Keys -T fields takes besides the NDJSON ones (tshark's frame.time_relative, time_delta, ..._displayed).
TIME_FIELDS = ("time_relative", "time_delta", "time_delta_displayed")


# What tshark's time column says of a time the platform's calendar cannot hold. The readers refuse
# such records (sources/common.py TIME_RANGE, issue 32); a library caller's own times may still be.
NOT_REPRESENTABLE = "Not representable"


# tshark's time precisions (wiretap's WTAP_TSPREC: s, ds, cs, ms, us, ns): the decimals of its time column.
PRECISIONS = (0, 1, 2, 3, 6, 9)
MICRO_DIGITS = 6  # a pcap's, a text log's, a live line's: microseconds
NANO_DIGITS = 9  # a nanosecond pcap's; the finest tshark holds (its nstime)


def column_digits(units: int | None) -> int:
    """The decimals tshark's time column shows of a file whose times are in 1/`units` s (a pcap's
    microseconds or nanoseconds, a pcapng interface's if_tsresol 10^-n or 2^-n): the finest of PRECISIONS
    they hold (tshark -r, 4.0: 9 for nanoseconds, 3 for if_tsresol 2^-10, 6 for 10^-7); 6 when unknown."""
    if not units:
        return MICRO_DIGITS
    return max(digits for digits in PRECISIONS if 10**digits <= units)


def detail_digits(units: int | None) -> int:
    """The decimals of -V's Arrival time (and its "since the first item") for a file whose times are in
    1/`units` s: 9, as tshark -V's Arrival Time shows its nanoseconds, where microseconds cannot hold them
    (a nanosecond pcap, if_tsresol 10^-7 or 2^-10, where the column shows 6 or 3: -w's rule,
    app/inputs.py write_units); else 6, as always."""
    return NANO_DIGITS if units and finer_than_micros(units) else MICRO_DIGITS


def whole_fraction(seconds: float, digits: int = MICRO_DIGITS, cut: bool = False) -> tuple[int, int]:
    """(whole seconds, the fraction in 1/10^digits s) of a time: from a Stamp's integer nanoseconds where
    it has them (a float of year 1 is -6.2e10 s, which keeps 8 us at best: .005000 showed .004997; near
    1.7e9 s one keeps 0.2 us), else the float's. Rounded, or `cut` as tshark cuts a capture's times to
    its precision (.142578125 s shows .142 in ms)."""
    scale = 10**digits
    ns = getattr(seconds, "ns", None)
    if ns is not None:
        whole, rest = divmod(ns, NANOS)
        fraction = rest * scale // NANOS if cut else round(rest * scale / NANOS)
    else:
        whole = int(seconds // 1)
        fraction = round((seconds - whole) * scale)
    if fraction == scale:  # 0.9999996 rounds up into the next second
        whole, fraction = whole + 1, 0
    return whole, fraction


def whole_micros(seconds: float) -> tuple[int, int]:
    """(whole seconds, microseconds) of a time (whole_fraction)."""
    return whole_fraction(seconds, MICRO_DIGITS)


def _decimals(fraction: int, digits: int) -> str:
    return f".{fraction:0{digits}d}" if digits else ""


def _clock_text(seconds: float, utc: bool, date: bool, digits: int = MICRO_DIGITS, cut: bool = False,
                year_day: bool = False) -> str:
    """`year_day`: the date as tshark's -t adoy/udoy write it, year/day of the year (2026/001)."""
    whole, fraction = whole_fraction(seconds, digits, cut)
    try:
        parts = _time.gmtime(whole) if utc else _time.localtime(whole)
        day = f"{parts.tm_year:04d}-{parts.tm_mon:02d}-{parts.tm_mday:02d} " if date else ""  # 0001, as tshark
        if year_day:
            day = f"{parts.tm_year:04d}/{parts.tm_yday:03d} "
        return f"{day}{_time.strftime('%H:%M:%S', parts)}{_decimals(fraction, digits)}"
    except (OverflowError, OSError, ValueError):  # outside time_t or the C library's years
        return NOT_REPRESENTABLE


def signed_text(ns: int, digits: int, cut: bool) -> str:
    """Seconds from integer nanoseconds, to `digits` decimals, its sign apart (cut toward zero, as tshark)."""
    whole, fraction = whole_fraction(Stamp(abs(ns)), digits, cut)
    return f"{'-' if ns < 0 and (whole or fraction) else ''}{whole}{_decimals(fraction, digits)}"


@dataclass(slots=True)
class Clock:
    """Turns item times into the text of the time column; one per input (times restart per input)."""

    format: str = "r"
    deltas: bool = False  # keep each item's previous captured time even when -t is not d (-e time_delta)
    # The input's time units a second (a pcap's, a pcapng's if_tsresol: None for others): the column shows
    # their precision (column_digits), its times cut to it as tshark's; the others' are rounded to us.
    units: int | None = None
    first: float | None = None  # time of the first timed item captured
    # A network capture's, an RTAC serial capture's (its header times: sources/common.py rtac_mark), or a serial
    # bus's of a pcapng with packets on several interfaces (sources/ethernet.py PacketTimes): r counts from its
    # first packet and d from the packet before the item's first, any packet, as tshark's frame.time_relative and
    # frame.time_delta (a packet with no bus bytes, another connection's or interface's, an RTAC event record, is
    # no item but a packet tshark shows); dd from the item shown before, as tshark -Y vw3's time_delta_displayed.
    packets: Any = None
    _previous_captured: float | None = None
    _previous_shown: float | None = None
    _before: dict[int, float | None] = field(default_factory=dict)  # id(item) -> previous captured time

    def reset(self) -> None:
        self.first = self._previous_captured = self._previous_shown = None
        self._before.clear()

    def observe(self, items: list[Item]) -> None:
        """See items as captured, before any display filter (call for every item, in order)."""
        track = self.deltas or self.format == "d"
        packets = network(self.packets)
        for item in items:
            time = item.time
            if time is None:
                continue
            if self.first is None:
                self.first = time if packets is None or packets.start is None else FirstPacket(packets.start)
            if track:
                self._before[id(item)] = self._previous_captured if packets is None else packet_before(packets, item)
            self._previous_captured = time

    @property
    def digits(self) -> int:
        return column_digits(self.units)

    def text(self, item: Item) -> str:
        """The column for an item being shown (call in display order)."""
        time = item.time
        if time is None:
            return UNTIMED
        fmt = self.format
        if fmt == "r":
            return self._since(time, self.first if self.first is not None else time)
        if fmt == "d":
            return self._since(time, self._before.pop(id(item), None))
        if fmt == "dd":
            previous, self._previous_shown = self._previous_shown, time
            return self._since(time, previous)
        cut = self.units is not None
        if fmt == "e":
            ns = getattr(time, "ns", None)  # (a float near 1.7e9 s keeps 0.2 us: not 9 decimals)
            return f"{time:.{self.digits}f}" if ns is None else signed_text(ns, self.digits, cut)
        return _clock_text(time, utc=fmt.startswith("u"), date=fmt.endswith("d"), digits=self.digits, cut=cut,
                           year_day=fmt.endswith("doy"))

    def _since(self, time: float, reference: float | None) -> str:
        """`time` less its reference (none: 0) to the column's decimals: a capture's from the stamps'
        nanoseconds, cut as tshark's; else rounded."""
        if reference is None:
            reference = time
        if self.units is not None and isinstance(time, Stamp) and isinstance(reference, Stamp):
            return signed_text(time.ns - reference.ns, self.digits, True)
        return f"{time - reference:.{self.digits}f}"

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


class FirstPacket(Stamp):
    """Clock.first when it is the capture's first packet's time (Clock.packets), not the first item's: -V's
    Arrival time says which (arrival_line), as tshark -V's `Time since reference or first frame`."""

    def __reduce__(self) -> tuple[type, tuple[int]]:
        return FirstPacket, (self.ns,)


# The words after the seconds of -V's Arrival time, by its base's type (a Stamp or a float: the first item's).
SINCE = {Stamp: " s since the first item)", FirstPacket: " s since the first packet)"}


def network(packets: Any) -> Any:
    """The PacketTimes the time column counts from, once its bus has a packet marked (a network capture's, an RTAC
    serial capture's, a serial bus's of a several-interface pcapng: sources/pcapng.py; none else)."""
    return packets if packets is not None and packets.offsets else None


def packet_before(packets: Any, item: Item) -> Stamp | None:
    """The time of the packet captured before the one where `item` starts (None: it is the first)."""
    before = packets.before(item.offset)
    return None if before is None else Stamp(before)


def utc_text(seconds: float, digits: int = MICRO_DIGITS) -> str:
    """-V's `YYYY-MM-DD HH:MM:SS.ffffff UTC` of a time, to `digits` decimals."""
    # datetime.fromtimestamp's own rounding (CPython _PyTime_DoubleToDenominator, half to even): the
    # whole second's text is kept (a capture's frames share their seconds), the microseconds appended.
    if not math.isfinite(seconds):
        return f"{seconds:.{digits}f}"
    if digits != MICRO_DIGITS or type(seconds) is not float and getattr(seconds, "ns", None) is not None:
        whole, micros = whole_fraction(seconds, digits)  # a Stamp: its integer nanoseconds (year 1 keeps them)
    else:
        fraction, whole = math.modf(seconds)
        micros = round(fraction * 1e6)
        if micros >= 1_000_000:
            micros -= 1_000_000
            whole += 1.0
        elif micros < 0:
            micros += 1_000_000
            whole -= 1.0
    second = SECONDS.get(whole)
    if second is None:
        try:
            moment = datetime.fromtimestamp(whole, tz=timezone.utc)
        except (OverflowError, OSError, ValueError):
            return f"{seconds:.{digits}f}"
        if len(SECONDS) >= 4096:
            SECONDS.clear()
        second = SECONDS[whole] = f"{moment.year:04d}-{moment:%m-%d %H:%M:%S}"
    return f"{second}.{micros:0{digits}d} UTC"


def arrival_line(time: float, base: float | None, digits: int = MICRO_DIGITS) -> str:
    """`    Arrival time: ... UTC (0.017823 s since the first item)` to `digits` decimals (`the first packet`
    where `base` is the capture's: FirstPacket): past 6, two Stamps' difference from their integer
    nanoseconds (a float near 1.7e9 s keeps 0.2 us)."""
    if digits != MICRO_DIGITS and type(time) is Stamp and isinstance(base, Stamp):
        since = signed_text(time.ns - base.ns, digits, True)
    else:
        since = f"{time - (base or 0.0):.{digits}f}"
    return f"    Arrival time: {utc_text(time, digits)} ({since}{SINCE.get(type(base), SINCE[Stamp])}"


SECONDS: dict[float, str] = {}  # a whole second's `YYYY-MM-DD HH:MM:SS` (bounded)
