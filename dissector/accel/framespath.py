"""Every other output of a timed capture (-V, --json, -T fields, --stats, --report, -Y, -w...) with the
framing, pairing and record reading in C: the engine (in `frames` mode, _judge.h) passes the clean
transactions it finds as records, and this module makes of them the very Frame objects the Python
framer and pairer would have made (offset, bytes, time, kind, number, the request and its answer, an
unanswered request), which the decoder and the annotator then take as usual; everything else (noise,
damage, broadcasts, late answers, silences inside frames...) the Python stages frame themselves, as the
timed summary path hands it over (timedpath.py). The renderers see the same items either way:
tests/differential/test_timed_outputs.py holds the outputs byte-identical to VW3_PURE_PYTHON=1.
"""
from __future__ import annotations

import struct
import weakref
from collections.abc import Callable, Iterable
from typing import Any

from dissector.accel import fastsummary
from dissector.decode.fields import decode_frame
from dissector.model import Chunk, Frame, Item, Kind, Stamp
from dissector.pipeline import Dissector
from dissector.render import bustiming
from dissector.render.timefmt import Clock

RECORD = struct.Struct("=qqiiBBBqq")  # _judge.h frames_record
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

    path = timedpath.TimedPath(dissector, None, Clock(), accept, lambda records: None, dissector.pairer.timeout)
    path.sync_clock = False  # (the engine writes no time column: the sinks' clock sees every item)
    path.engine.judge = _NOTHING
    path.engine.frames = True
    path.write_lines = _Frames(path, annotate, accept)
    for block in blocks_from_chunks(chunks, dissector.framer.timing):
        path.feed(block)
        warn()
        if sinks.done:  # -c N reached: the rest is not read (as decode_chunks)
            return True
    path.finish()
    warn()
    return True


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
        for q_at, a_at, q_length, a_length, a_kind, q_timed, a_timed, q_ns, a_ns in RECORD.iter_unpack(records):
            raw = buf[q_at : q_at + q_length]
            crc = raw[-2] | raw[-1] << 8
            request = Frame(base + q_at, raw, Stamp(q_ns) if q_timed else None, Kind.REQUEST, raw[0], raw[1] & 0x7F,
                            crc, crc)
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
