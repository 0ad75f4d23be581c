"""Pairing: link each response to the request it answers, and say which requests went unanswered.

Runs after the framer, which has already classified every frame. A request to slave 0 is a broadcast
and expects no answer. A request followed by another request (or by the end of the capture) was not
answered. With `hold=True` (files), a request is held back until the next frame tells whether it was
answered, so its own line can say so, as tshark's second pass would. With `hold=False` (live), every
item is released at once, and the next request carries the note instead.
"""
from __future__ import annotations

import weakref

from dissector.model import Frame, Item, Kind

HOLD_LIMIT = 64  # items held behind an open request before it is released anyway


class Pairer:
    def __init__(self, hold: bool = True, timeout: float | None = None) -> None:
        self._hold = hold
        self._timeout = timeout
        self._pending: Frame | None = None
        self._pending_released = False
        self._queue: list[Item] = []
        self._count = 0

    @property
    def idle(self) -> bool:
        """No request awaits its answer and nothing is held back."""
        return self._pending is None and not self._queue

    @property
    def count(self) -> int:
        """Items numbered so far."""
        return self._count

    @count.setter
    def count(self, value: int) -> None:
        self._count = value

    def push(self, items: list[Item]) -> list[Item]:
        out: list[Item] = []
        for item in items:
            self._push_one(item, out)
        return out

    def finish(self) -> list[Item]:
        out: list[Item] = []
        pending = self._pending
        if pending is not None:
            pending.unanswered = True
            if not self._pending_released:
                pending.notes.append("the capture ends before any response")
        self._pending = None
        self._release(out)
        return out

    # -- internals ---------------------------------------------------------------------------
    def _release(self, out: list[Item]) -> None:
        count = self._count
        for queued in self._queue:
            count += 1
            queued.number = count
            out.append(queued)
        self._count = count
        self._queue.clear()
        if self._pending is not None:
            self._pending_released = True

    def _push_one(self, item: Item, out: list[Item]) -> None:
        if not isinstance(item, Frame):
            self._enqueue(item, out)
            return
        pending = self._pending
        if item.kind is Kind.REQUEST:
            if pending is not None:
                pending.unanswered = True
                if self._pending_released:
                    item.notes.append(f"request #{pending.number} was not answered")
            self._pending = None
            self._release(out)
            if item.slave == 0:
                item.broadcast = True
                self._enqueue(item, out)
                return
            self._pending = item
            self._pending_released = False
            self._queue.append(item)
            if not self._hold:
                self._release(out)
            return
        # A response or an exception.
        if pending is not None and pending.slave == item.slave and pending.function == item.function:
            item.request = pending
            pending.response_ref = weakref.ref(item)
            self._pending = None
            if self._timeout is not None and item.time is not None and pending.time is not None:
                if item.time - pending.time > self._timeout:
                    item.warnings.append(
                        f"response after {item.response_time * 1000:.1f} ms, later than the "
                        f"{self._timeout * 1000:.0f} ms timeout"
                    )
        else:
            if pending is not None:
                pending.unanswered = True
                if self._pending_released:
                    item.notes.append(f"request #{pending.number} was not answered")
                self._pending = None
            item.notes.append("response without a matching request in the capture")
        self._queue.append(item)
        self._release(out)

    def _enqueue(self, item: Item, out: list[Item]) -> None:
        self._queue.append(item)
        if self._pending is None or not self._hold or len(self._queue) > HOLD_LIMIT:
            self._release(out)
