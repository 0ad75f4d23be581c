"""Stream offsets in ascending order with set membership: the record ends, record starts and silences a framer
weighs. The framer asks for the first one after a point and for those inside a window; a plain set answered
both by a scan of all of them, which on a capture of one-byte reads (a USB tap, a line at the wrong speed) made
each byte cost the whole buffer's offsets, several times over (hundreds of times the cost of raw bytes)."""
from __future__ import annotations

from bisect import bisect_left, bisect_right, insort
from heapq import heapify
from collections.abc import Iterable, Iterator


class Offsets:
    __slots__ = ("_ordered", "_members")

    def __init__(self) -> None:
        self._ordered: list[int] = []
        self._members: set[int] = set()

    def add(self, offset: int) -> None:
        if offset in self._members:
            return
        self._members.add(offset)
        if not self._ordered or offset > self._ordered[-1]:
            self._ordered.append(offset)  # (the usual case: offsets come as the stream grows)
        else:
            insort(self._ordered, offset)

    def update(self, offsets: Iterable[int]) -> None:
        for offset in offsets:
            self.add(offset)

    def __contains__(self, offset: int) -> bool:
        return offset in self._members

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Offsets) and self._ordered == other._ordered

    __hash__ = None  # type: ignore[assignment]  # (mutable, as a set)

    def __repr__(self) -> str:
        return f"Offsets({self._ordered})"

    def __bool__(self) -> bool:
        return bool(self._ordered)

    def __iter__(self) -> Iterator[int]:
        return iter(self._ordered)

    def drop_below(self, offset: int) -> None:
        """Forget the offsets before `offset` (the buffer's new base)."""
        count = bisect_left(self._ordered, offset)
        if count:
            self._members.difference_update(self._ordered[:count])
            del self._ordered[:count]

    def first_after(self, low: int, high: int) -> int | None:
        """The first offset o with low < o <= high, or None."""
        at = bisect_right(self._ordered, low)
        return self._ordered[at] if at < len(self._ordered) and self._ordered[at] <= high else None

    def within(self, low: int, high: int) -> list[int]:
        """The offsets o with low <= o < high, in ascending order."""
        ordered = self._ordered
        return ordered[bisect_left(ordered, low) : bisect_left(ordered, high)]


class EndAnswers:
    """The record ends' answers (reach.py RecordEnds._record_end) under one state (the answer awaited, its echo): by offset
    the answer and the stream end up to which it holds, the offsets answered True in order, a heap of the answers
    by that end (asked again when the stream reaches it), and the span low..high whose every record end is
    answered. A scan asks only the answers the bytes come since may change and the record ends new to it: its
    first frame of its own is the first True in its span (one-byte records: a few answers a byte, not 256)."""

    def __init__(self) -> None:
        self.reset((None, None))

    def reset(self, state: tuple[tuple[int, int] | None, bytes] | tuple[None, None]) -> None:
        self.state = state
        self.last = -1
        # offset -> (answer, the stream end up to which it holds, the (slave, function) its bytes start with)
        self.answers: dict[int, tuple[bool, int, tuple[int, int]]] = {}
        self.trues: list[int] = []
        self.expiry: list[tuple[int, int]] = []
        self.starts: dict[tuple[int, int], list[int]] = {}  # (slave, function) -> the record ends starting so
        self.low = self.high = -1

    def prune(self, base: int, most: int) -> bool:
        """Forget the answers at or before `base` (bytes framed: never weighed again); False when more than
        `most` stay (reset then)."""
        answers = {offset: answer for offset, answer in self.answers.items() if offset > base}
        if len(answers) > most:
            return False
        self.answers = answers
        self.trues = [offset for offset in self.trues if offset > base]
        self.expiry = [(until, offset) for until, offset in self.expiry if offset > base]
        heapify(self.expiry)
        self.starts = {}
        for offset, (_answer, _until, key) in answers.items():
            self.starts.setdefault(key, []).append(offset)
        self.low, self.high = max(self.low, base + 1), max(self.high, base + 1)
        return True
