"""A date and time in double quotes for `time` in display filters (`-Y 'time >= "2026-12-05 10:00:00"'`),
read as tshark 4 reads one for frame.time: ISO (`2026-12-05`, `2026-12-05 10:00`, `2026-12-05T10:00:00.25`)
or tshark's own (`Dec  5, 2026 10:00:00.25`), in local time (the time column's -t ad) unless it ends in
`Z`, ` UTC` or an offset (`+01:00`). The result is seconds since the epoch, as --json's `time`, exact to
the nanosecond written (compared equal to a pcap's time as `Stamp` holds it: model.py)."""
from __future__ import annotations

import calendar
import datetime
import re

MONTHS = ("jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec")
_CLOCK = (r"(?:(?:T|\s+)(?P<hour>\d{1,2}):(?P<minute>\d{2})"
          r"(?::(?P<second>\d{2})(?:\.(?P<fraction>\d{1,9}))?)?)?")
_ZONE = r"\s*(?P<zone>Z|UTC|[+-]\d{2}:?\d{2})?"
ISO = re.compile(r"(?P<year>\d{4})-(?P<month>\d{1,2})-(?P<day>\d{1,2})" + _CLOCK + _ZONE, re.IGNORECASE)
TSHARK = re.compile(r"(?P<month>[A-Za-z]{3})\s+(?P<day>\d{1,2}),\s*(?P<year>\d{4})" + _CLOCK + _ZONE,
                    re.IGNORECASE)
EXAMPLES = ('"2026-12-05 10:00:00" or "Dec  5, 2026 10:00:00.5" '
            "(local time; Z, UTC or +01:00 for another zone)")


def absolute_time(text: str) -> float | None:
    """Seconds since the epoch that `text` names, or None when it is no date and time of these forms."""
    match = ISO.fullmatch(text.strip()) or TSHARK.fullmatch(text.strip())
    if match is None:
        return None
    month = match["month"]
    if not month.isdigit():
        if month.lower() not in MONTHS:
            return None
        month = str(MONTHS.index(month.lower()) + 1)
    try:
        moment = datetime.datetime(int(match["year"]), int(month), int(match["day"]), int(match["hour"] or 0),
                                   int(match["minute"] or 0), int(match["second"] or 0))
    except ValueError:  # 2026-13-01, Feb 30, 25:00
        return None
    zone = (match["zone"] or "").upper()
    if not zone:
        seconds = int(moment.timestamp())  # (a naive datetime is local time)
    else:
        seconds = calendar.timegm(moment.timetuple())
        if zone not in ("Z", "UTC"):
            sign = -1 if zone[0] == "-" else 1
            digits = zone[1:].replace(":", "")
            seconds -= sign * (int(digits[:2]) * 3600 + int(digits[2:]) * 60)
    nanoseconds = int((match["fraction"] or "").ljust(9, "0"))
    return (seconds * 1_000_000_000 + nanoseconds) / 1_000_000_000  # (int / int rounds once, as Stamp's)
