"""Every other output of a timed capture (-V, --json, -T fields, --stats, --report, -Y, -w...) with the
framing, pairing and record reading in C: the engine (in `frames` mode, _judge.h) passes the clean
transactions it finds as records, and this module makes of them the very Frame objects the Python
framer and pairer would have made (offset, bytes, time, kind, number, the request and its answer, an
unanswered request), which the decoder and the annotator then take as usual; everything else (noise,
damage, broadcasts, late answers, silences inside frames...) the Python stages frame themselves, as the
timed summary path hands it over (timedpath.py). The renderers see the same items either way:
tests/differential/test_timed_outputs.py holds the outputs byte-identical to VW3_PURE_PYTHON=1.

With -c N the Python stages (app/paths.py decode_chunks) stop after the chunk whose items reach the Nth
item (frame or noise run: each a packet, app/cli.py Sinks._up_to_count): everything that chunk gave
(items after the Nth too) went through the decoder, the annotator, the bus timing and the report,
nothing after it. The engine frames many transactions in one run, so here it is given only bytes that
cannot hold the Nth item: an item is at least a byte and items do not share bytes, so while the bytes
given and not yet come out as items are fewer than the items still to show, none among them can be
the Nth (_Counted.room). Blocks are
built up to that size and a chunk (the source reads no record, nor warns of one, that the Python stages
would not read) and cut at a chunk before it; at the first chunk that might hold the Nth item the
Python stages take the stream, as TimedPath.finish takes it, and go on chunk by chunk as decode_chunks
does. tests/differential/test_count_engine.py and test_count_cut.py hold -c N byte-identical to
VW3_PURE_PYTHON=1.
"""
from __future__ import annotations

import struct
import weakref
from bisect import bisect_left
from collections.abc import Callable, Iterable
from itertools import chain
from typing import Any

from dissector.accel import fastsummary
from dissector.accel.records import Block
from dissector.decode.fields import decode_frame
from dissector.model import Chunk, Frame, Item, Kind, Stamp
from dissector.pipeline import Dissector
from dissector.render import bustiming
from dissector.render.timefmt import Clock

RECORD = struct.Struct("=qqiiBBBqqqqii")  # _judge.h frames_record
_KINDS = {number: kind for kind, number in bustiming._KINDS.items()}  # (an answer's: response, exception)
_NOTHING = bytes(256 * 32)  # no (slave, function) is the Python stages' alone
SLICE = 256  # transactions decoded and shown at a time


def decode(chunks: Iterable[Chunk], dissector: Dissector, sinks: Any, annotate: Any | None,
           warn: Callable[[], None]) -> bool:
    """Decode a timed input into `sinks` (app/cli.py) with the engine's framing; False (nothing read)
    when the engine is not available."""
    from dissector.accel import timedpath
    from dissector.accel.records import blocks_from_chunks

    if not fastsummary.available() or not fastsummary.built():
        return False
    def accept(items: list[Item]) -> None:
        if not sinks.done:  # -c N: nothing after the frame that reached it
            sinks.accept(items)

    counted = _Counted(dissector, sinks, warn) if sinks.frames_left is not None else None
    if counted is not None:
        accept = counted.accept
    path = timedpath.TimedPath(dissector, None, Clock(), accept, lambda records: None, dissector.pairer.timeout)
    path.sync_clock = False  # (the engine writes no time column: the sinks' clock sees every item)
    path.judge = _NOTHING
    path.engine.frames = True
    path.write_lines = _Frames(path, annotate, accept)
    if counted is not None:
        counted.run(chunks, path)
        return True
    for block in blocks_from_chunks(chunks, dissector.framer.timing):
        path.feed(block)
        warn()
    path.finish()
    warn()
    return True


class _Counted:
    """-c N: the engine given bytes that cannot hold the Nth item, the Python stages the rest (above)."""

    def __init__(self, dissector: Dissector, sinks: Any, warn: Callable[[], None]) -> None:
        self.dissector = dissector
        self.sinks = sinks
        self.warn = warn
        self.given = 0  # bytes given to the engine's path
        self.out = 0  # bytes of the items it gave out

    def accept(self, items: list[Item]) -> None:
        for item in items:
            self.out += item.length
        if not self.sinks.done:
            self.sinks.accept(items)

    def room(self) -> int:
        """Bytes that may be given to the engine's path with no item among them the Nth."""
        return self.sinks.frames_left - (self.given - self.out)

    def run(self, chunks: Iterable[Chunk], path: Any) -> None:
        from dissector.accel.records import BlockBuilder, blocks_from_chunks

        timing = self.dissector.framer.timing
        builder = BlockBuilder(timing, getattr(chunks, "streaming", False))
        most = builder.block_bytes
        builder.block_bytes = max(1, min(most, self.room()))
        blocks = blocks_from_chunks(chunks, timing, builder)
        for block in blocks:
            rest = self._engine(block, path)
            if rest is not None:
                builder.block_bytes = 1  # a chunk at a time from now on, as decode_chunks reads them
                self._python(rest, blocks, path)
                return
            self.warn()
            builder.block_bytes = max(1, min(most, self.room()))
        path.finish()
        self.warn()

    def _engine(self, block: Block, path: Any) -> Block | None:
        """The block's chunks to the engine's path while they cannot hold the Nth item; the rest, if any."""
        while True:
            starts = block.starts
            room = self.room()
            count = bisect_left(starts, starts[0] + room)  # chunks starting within the room
            if count == len(starts) and len(block.data) < room:
                self.given += len(block.data)
                path.feed(block)
                return None
            count -= 1  # the last of them may end past it
            if count <= 0:
                return block
            head, block = _split(block, count)
            self.given += len(head.data)
            path.feed(head)

    def _python(self, block: Block, blocks: Iterable[Block], path: Any) -> None:
        """The Python stages from the chunk that may hold the Nth item on, as decode_chunks: chunk by
        chunk, up to the chunk that reaches it."""
        dissector = self.dissector
        if self.given:  # (else they have all the stream already)
            if not path.python:
                path._hand_over()
            dissector.framer.pause_at(None)
            for index in range(path.fed, len(path.starts)):
                if self._chunk(path._chunk(index)):
                    return
        for each in chain([block], blocks):
            for index in range(len(each.starts)):
                if self._chunk(each.chunk(index)):
                    return
        self.accept(dissector.finish())
        self.warn()

    def _chunk(self, chunk: Chunk) -> bool:
        self.accept(self.dissector.feed(chunk))
        self.warn()
        return self.sinks.done


def _split(block: Block, count: int) -> tuple[Block, Block]:
    """A block's first `count` chunks, and the rest."""
    cut = block.starts[count] - block.starts[0]
    kept = block.chunks
    return (Block(block.data[:cut], block.starts[:count], block.times[:count], block.flags[:count], block.exact,
                  kept[:count]),
            Block(block.data[cut:], block.starts[count:], block.times[count:], block.flags[count:], block.exact,
                  kept[count:]))


class _Frames:
    """The engine's records into decoded, annotated, numbered frames, in the Python stages' form."""

    def __init__(self, path: Any, annotate: Any | None, accept: Callable[[list[Item]], None]) -> None:
        self.path = path
        self.annotate = annotate
        self.accept = accept
        self.numbered = 0  # items numbered so far
        # Live -c N (livepath.py): the frames of a slice kept, before they are decoded and annotated.
        self.cut: Callable[[list[Item]], list[Item]] | None = None

    def __call__(self, records: bytes) -> None:
        # A slice of records at a time: only that many decoded frames are alive at once (memory flat).
        self.numbered = self.path.numbered
        for start in range(0, len(records), SLICE * RECORD.size):
            self._frames(records[start : start + SLICE * RECORD.size])

    def _frames(self, records: bytes) -> None:
        path = self.path
        buf, base = path.buf, path.base
        number = self.numbered
        annotate = self.annotate
        items: list[Item] = []
        for (q_at, a_at, q_length, a_length, a_kind, q_timed, a_timed, q_ns, a_ns, q_tail_ns, a_tail_ns, q_tail,
             a_tail) in RECORD.iter_unpack(records):
            raw = buf[q_at : q_at + q_length]
            crc = raw[-2] | raw[-1] << 8
            request = Frame(base + q_at, raw, Stamp(q_ns) if q_timed else None, Kind.REQUEST, raw[0], raw[1] & 0x7F,
                            crc, crc)
            if q_tail != q_length or q_tail_ns != q_ns:  # (its last byte in a later chunk: model.sent_in)
                request.tail = (Stamp(q_tail_ns), q_tail)
            number += 1
            request.number = number
            items.append(request)
            if a_at < 0:
                request.unanswered = True
            else:
                raw = buf[a_at : a_at + a_length]
                crc = raw[-2] | raw[-1] << 8
                answer = Frame(base + a_at, raw, Stamp(a_ns) if a_timed else None, _KINDS[a_kind], raw[0],
                               raw[1] & 0x7F, crc, crc)
                if a_tail != a_length or a_tail_ns != a_ns:
                    answer.tail = (Stamp(a_tail_ns), a_tail)
                number += 1
                answer.number = number
                answer.request = request
                request.response_ref = weakref.ref(answer)
                items.append(answer)
        self.numbered = number
        if self.cut is not None:
            items = self.cut(items)
        for item in items:
            decode_frame(item)  # type: ignore[arg-type]
            if annotate is not None:
                annotate(item)
        self.accept(items)
