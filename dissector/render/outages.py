"""Outages (render/bustiming.py): two or more consecutive requests to a slave left unanswered, from the
first to the last, with their count and frames. Several files read as one bus number their frames each
from 1: an outage keeps the files of its first and last request (`first_input`, `last_input`: the
count of BusTiming.new_input, from 0) and cites its frames with them, as selection.Cited cites a frame.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(slots=True)
class Outage:
    slave: int
    start: float | None  # time of the first unanswered request
    end: float | None  # time of the last
    requests: int
    first_frame: int
    last_frame: int
    offset: int = 0  # the first unanswered request's, in the input stream
    first_input: int = 0  # the files of the first and last (BusTiming.new_input's count, from 0)
    last_input: int = 0

    def as_dict(self, titles: list[str] | None = None) -> dict[str, Any]:
        """`titles`: the names of several files read as one bus (their frames numbered each from 1): the
        files of its first and last frame are said (`file`, `last_file`)."""
        data = {"slave": self.slave, "start": self.start, "end": self.end, "requests": self.requests,
                "first_frame": self.first_frame, "last_frame": self.last_frame}
        if titles:
            data["file"], data["last_file"] = titles[self.first_input], titles[self.last_input]
        return data


def frames_cited(outage: dict[str, Any], mark: str = "") -> str:
    """An outage's frames (as_dict's): `7..8`, of several files `7..8 of t1.pcap` (selection.Cited's way),
    `7 of t1.pcap..1 of t2.pcap` over two; `mark` goes before each number (the report's `#`)."""
    first, last = f"{mark}{outage['first_frame']}", f"{mark}{outage['last_frame']}"
    file, last_file = outage.get("file"), outage.get("last_file")
    if file is None:
        return f"{first}..{last}"
    return f"{first}..{last} of {file}" if file == last_file else f"{first} of {file}..{last} of {last_file}"


@dataclass(slots=True)
class Run:
    """A slave's unanswered requests so far (an outage once it ends with two or more)."""

    start: float | None
    end: float | None
    requests: int
    first_frame: int
    last_frame: int
    offset: int
    first_input: int
    last_input: int
