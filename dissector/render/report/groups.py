"""The report's events grouped by kind, slave and what happened (`CHCF (8401) protected`, `exception 02
to function 3`), each with its count and its first and last moment and frame: a day of one recurring
exception is one line, not a thousand. Numbers that vary between occurrences of the same event
(noise offsets and lengths, silence durations, CRC values) do not split a group; its text shows each
such number as the range its occurrences cover (`4..5 bytes of noise at offset 0..307`), never the
first occurrence's alone. Nor does a count's noun, singular for one (`1 byte of noise`, describe.count_text):
the label reads it singular when the count is 1 in every occurrence, plural otherwise (`1..4 bytes`).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

MAX_GROUPS = 2000
_VARYING = re.compile(r"\d+(?:\.\d+)?")
# A varying number and the noun it counts, if one follows (`1 byte`, `4 bytes`): the noun is read
# from the group's range of that number, never from its first occurrence.
_COUNTED = re.compile(r"(\d+(?:\.\d+)?)(?:( byte)s?\b)?")
_NOUN = re.compile(r"(N byte)s?\b")
_VARYING_KINDS = frozenset(["noise", "silence", "crc", "unanswered"])


@dataclass(slots=True)
class Group:
    kind: str
    slave: int | None
    text: str  # the first occurrence's text
    count: int
    first_x: float
    first_frame: int
    last_x: float
    last_frame: int
    # Per varying number of the text, in order: (lowest, its text, highest, its text).
    ranges: list[tuple[float, str, float, str]] | None = None
    detail: str | None = None  # a protection event's registers, each told (collect.py, moments.py)

    def widen(self, text: str) -> None:
        numbers = _VARYING.findall(text)
        if self.ranges is None or len(numbers) != len(self.ranges):
            return
        for index, number in enumerate(numbers):
            low, low_text, high, high_text = self.ranges[index]
            value = float(number)
            if value < low:
                low, low_text = value, number
            if value > high:
                high, high_text = value, number
            self.ranges[index] = (low, low_text, high, high_text)

    @property
    def label(self) -> str:
        """The text, each varying number the range of its occurrences (`4..5 bytes of noise`)."""
        if not self.ranges:
            return self.text
        pieces = iter(self.ranges)

        def shown(match: re.Match[str]) -> str:
            low, low_text, high, high_text = next(pieces)
            number = low_text if low == high else f"{low_text}..{high_text}"
            if match[2] is None:
                return number
            return f"{number}{match[2]}" if number == "1" else f"{number}{match[2]}s"

        return _COUNTED.sub(shown, self.text)


class EventGroups:
    """Events by (kind, slave, what): counts, first and last. Past MAX_GROUPS, new groups are counted apart."""

    def __init__(self) -> None:
        self.groups: dict[tuple[str, int | None, str], Group] = {}
        self.ungrouped = 0

    def add(self, kind: str, slave: int | None, text: str, x: float, frame: int, detail: str | None = None) -> None:
        what = _NOUN.sub(r"\1s", _VARYING.sub("N", text)) if kind in _VARYING_KINDS else text
        key = (kind, slave, what if detail is None else f"{what}\n{detail}")  # (a span's other statuses: another)
        group = self.groups.get(key)
        if group is None:
            if len(self.groups) >= MAX_GROUPS:
                self.ungrouped += 1
                return
            ranges = None
            if kind in _VARYING_KINDS:
                ranges = [(float(number), number, float(number), number) for number in _VARYING.findall(text)]
            self.groups[key] = Group(kind, slave, text, 1, x, frame, x, frame, ranges, detail)
            return
        group.count += 1
        group.last_x, group.last_frame = x, frame
        if group.ranges:
            group.widen(text)

    def retell(self, kind: str, slave: int | None, text: str, new: str) -> None:
        """The occurrences told as `text` told as `new` (an exception's meaning known later): their group
        under the new text, joined with the one already there (an event of no varying number)."""
        group = self.groups.pop((kind, slave, text), None)
        if group is None:
            return
        group.text = new
        there = self.groups.get((kind, slave, new))
        if there is None:
            self.groups[(kind, slave, new)] = group
            return
        there.count += group.count
        if (group.first_x, group.first_frame) < (there.first_x, there.first_frame):
            there.first_x, there.first_frame = group.first_x, group.first_frame
        if (group.last_x, group.last_frame) > (there.last_x, there.last_frame):
            there.last_x, there.last_frame = group.last_x, group.last_frame

    def rows(self) -> list[Group]:
        return sorted(self.groups.values(), key=lambda group: (group.first_x, group.first_frame))
