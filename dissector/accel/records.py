"""A timed source's chunks in blocks, for the compiled path (timedpath.py): the bytes of many chunks
at once, with per chunk its stream offset, its time in integer nanoseconds and its flags (_timeline.h:
timed, a record ends after it, a silence of t3.5 before it). The engine reads the arrays in one call
instead of one call per record; the Python stages get the very chunks back (Block.chunk) where they
take the stream.

The silence flag is the framer's own rule (timing.silence_before, from the chunk before), so both
sides weigh the same boundaries.
"""
from __future__ import annotations

from array import array
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from dissector.framing.timing import LineTiming, silence_before
from dissector.model import Chunk, Stamp

TIMED, RECORD_END, SILENCE_BEFORE = 1, 2, 4  # _timeline.h CHUNK_*
BLOCK_BYTES = 1 << 18  # bytes gathered before the engine runs: memory stays flat, calls few


@dataclass(slots=True)
class Block:
    data: bytes
    starts: array  # int64 stream offsets
    times: array  # int64 ns (0 where untimed)
    flags: bytearray
    exact: bool = True  # every time is a Stamp (integer ns): the engine can subtract them as Python does
    chunks: list[Chunk] = field(default_factory=list)

    def chunk(self, index: int) -> Chunk:
        return self.chunks[index]


def blocks_from_chunks(chunks: Iterable[Chunk], timing: LineTiming) -> Iterator[Block]:
    """Blocks of the chunks a source gives (any source: pcapng, RTAC records, hex dumps...)."""
    offset = 0
    previous: tuple[int, float | None] | None = None
    pieces: list[bytes] = []
    kept: list[Chunk] = []
    starts, times, flags = array("q"), array("q"), bytearray()
    size = 0
    exact = True
    for chunk in chunks:
        data = chunk.data
        if not data:
            continue
        time = chunk.time
        flag = RECORD_END if chunk.boundary else 0
        ns = 0
        if time is not None:
            flag |= TIMED
            if isinstance(time, Stamp):
                ns = time.ns
            else:
                exact = False
            if previous is not None and silence_before(previous, offset, time, timing):
                flag |= SILENCE_BEFORE
        previous = (offset, time)
        pieces.append(data)
        kept.append(chunk)
        starts.append(offset)
        times.append(ns)
        flags.append(flag)
        offset += len(data)
        size += len(data)
        if size >= BLOCK_BYTES:
            yield Block(b"".join(pieces), starts, times, flags, exact, kept)
            pieces, kept = [], []
            starts, times, flags = array("q"), array("q"), bytearray()
            size = 0
    if kept:
        yield Block(b"".join(pieces), starts, times, flags, exact, kept)
