"""Wiring of the stages: source chunks -> framer -> pairer -> decoder -> annotator -> items.

Each stage is a plain object or function; this module only connects them, in one direction.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from typing import Protocol

from dissector.decode.fields import decode_frame
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame, Item, stamped_before
from dissector.decode.pairing import Pairer
from dissector.framing.timing import GapChecker


class Framer(Protocol):
    mode: str

    def feed(self, chunk: Chunk) -> list[Item]: ...

    def finish(self) -> list[Item]: ...

    def finish_at(self, end: float | None) -> list[Item]: ...


Annotator = Callable[[Frame], None]


class Dissector:
    """Push interface over the whole chain; `feed` returns the items that are complete."""

    def __init__(
        self,
        framer: Framer | None = None,
        annotate: Annotator | None = None,
        hold: bool = True,
        timeout: float | None = None,
        gaps: GapChecker | None = None,
        live: bool = False,
        recorded: Callable[[], float | None] | None = None,
        char_time: float | None = None,
    ) -> None:
        self.framer = framer if framer is not None else RtuFramer()
        # A request's timeout starts once it is sent: its characters' time at the line's speed (`char_time`:
        # the framer's line by default; live, the capture thread's framer's).
        self.pairer = Pairer(hold=hold, timeout=timeout,
                             char_time=self.framer.timing.char_time if char_time is None else char_time)
        self.annotate = annotate
        self.gaps = gaps
        # A file ends when its last bytes came (a request within its timeout of that: not known whether it
        # was answered); live, when the clock says (expire: a request past its timeout is unanswered).
        self._stamps_end = not live
        # A file: asked at its end when its tap last recorded, later than its last bytes where another
        # bus's records (a pcapng's other interfaces) or an empty record went on (Source.recorded_until).
        self.recorded = recorded
        # --hex: the typed bytes put back in frames framed from mended ones (app/hexinput.py HexInput.fix),
        # before they are decoded: a CRC typed bad is judged bad by the annotator as by every output.
        self.fix: Callable[[list[Item]], list[Item]] | None = None

    def _finish_items(self, items: list[Item]) -> list[Item]:
        if self.fix is not None:
            items = self.fix(items)
        annotate = self.annotate
        gaps = self.gaps
        for item in items:
            if gaps is not None:
                item.warnings.extend(gaps.check(item))  # noise too: it lets the checker forget
            if isinstance(item, Frame):
                decode_frame(item)
                if annotate is not None:
                    annotate(item)
        return items

    def feed(self, chunk: Chunk) -> list[Item]:
        if self.gaps is not None:
            self.gaps.observe(chunk)
        if self._stamps_end and chunk.data and chunk.time is not None:
            self.pairer.end = chunk.time
        return self._finish_items(self.pairer.push(self.framer.feed(chunk)))

    def push(self, items: list[Item]) -> list[Item]:
        """Items a framer gave out elsewhere (the live capture thread): pair, decode, annotate."""
        return self._finish_items(self.pairer.push(items))

    def expire(self, now: float) -> list[Item]:
        """Live: no frame earlier than `now` is still to come; a request past its timeout is final."""
        return self._finish_items(self.pairer.expire(now))

    def flush_idle(self) -> list[Item]:
        """After a silence on a live line: what the framer holds is complete, or noise.

        Framers promise that finish() consumes their buffer and leaves them ready for more bytes
        (RtuFramer and AsciiFramer keep their expectation); the pairer is not finished, so a
        response that comes later still pairs with its request.
        """
        return self._finish_items(self.pairer.push(self.framer.finish()))

    def finish(self) -> list[Item]:
        recorded = self.recorded() if self._stamps_end and self.recorded is not None else None
        if recorded is not None and (self.pairer.end is None or stamped_before(self.pairer.end, recorded)):
            self.pairer.end = recorded
        # The capture ends then (a file: its last record; live: the stop, set by the display): what the framer
        # holds is cut by a silence before it or by the end, by the line's one rule (StreamFramer.finish_at).
        items = self.pairer.push(self.framer.finish_at(self.pairer.end))
        items += self.pairer.finish()
        return self._finish_items(items)


def dissect(chunks: Iterable[Chunk], **options: object) -> Iterator[Item]:
    dissector = Dissector(**options)  # type: ignore[arg-type]
    for chunk in chunks:
        yield from dissector.feed(chunk)
    yield from dissector.finish()


def dissect_bytes(data: bytes, **options: object) -> list[Item]:
    return list(dissect([Chunk(data)], **options))
