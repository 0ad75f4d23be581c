"""The report's events grouped by kind, slave and what happened (`CHCF (8401) protected`, `exception 02
to function 3`), each with its count and its first and last moment and frame: a day of one recurring
exception is one line, not a thousand. Numbers that vary between occurrences of the same event
(noise offsets and lengths, silence durations, CRC values) do not split a group.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

MAX_GROUPS = 2000
_VARYING = re.compile(r"\d+(?:\.\d+)?")
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


class EventGroups:
    """Events by (kind, slave, what): counts, first and last. Past MAX_GROUPS, new groups are counted apart."""

    def __init__(self) -> None:
        self.groups: dict[tuple[str, int | None, str], Group] = {}
        self.ungrouped = 0

    def add(self, kind: str, slave: int | None, text: str, x: float, frame: int) -> None:
        what = _VARYING.sub("N", text) if kind in _VARYING_KINDS else text
        key = (kind, slave, what)
        group = self.groups.get(key)
        if group is None:
            if len(self.groups) >= MAX_GROUPS:
                self.ungrouped += 1
                return
            self.groups[key] = Group(kind, slave, text, 1, x, frame, x, frame)
            return
        group.count += 1
        group.last_x, group.last_frame = x, frame

    def rows(self) -> list[Group]:
        return sorted(self.groups.values(), key=lambda group: (group.first_x, group.first_frame))
