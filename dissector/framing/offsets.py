"""Stream offsets in ascending order with set membership: the record ends, record starts and silences a framer
weighs. The framer asks for the first one after a point and for those inside a window; a plain set answered
both by a scan of all of them, which on a capture of one-byte reads (a USB tap, a line at the wrong speed) made
each byte cost the whole buffer's offsets, several times over (hundreds of times the cost of raw bytes)."""
from __future__ import annotations

from bisect import bisect_left, bisect_right, insort
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
