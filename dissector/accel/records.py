"""A timed source's chunks in blocks, for the compiled path (timedpath.py): the bytes of many chunks
at once, with per chunk its stream offset, its time in integer nanoseconds and its flags (_timeline.h:
timed, a record ends after it, a silence of t3.5 before it). The engine reads the arrays in one call
instead of one call per record; the Python stages get the very chunks back (Block.chunk) where they
take the stream.

Classic pcap records are read in bulk by the engine's scan_pcap (_records.h), a megabyte at a time,
as sources/pcap.py reads them; a record that reader must see itself (one captured in part, one longer
than a chunk: their warnings and splits) and the rest after it go through it. A record captured in part is
a cut (framing/stream.py _cut_part) the engine does not make: the Python stages frame across it
(timedpath.py cut_until). Every other source's
chunks (pcapng, hex dumps...) are gathered as they come. The silence flag is the framer's own rule
(timing.silence_before, from the chunk before), so both sides weigh the same boundaries.
"""
from __future__ import annotations

import struct
from array import array
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from itertools import chain, islice
from typing import TYPE_CHECKING, Any

from dissector.framing.timing import LineTiming, silence_before
from dissector.model import Chunk, Stamp
from dissector.sources.common import LINKTYPE_USER0, PartChunk
from dissector.sources.pcap import empty_records

if TYPE_CHECKING:
    from dissector.sources.trail import RecordTrail

TIMED, RECORD_END, SILENCE_BEFORE = 1, 2, 4  # the engine's CHUNK_* (generated into _tables.h)
TIMED_ONLY = bytes(flag & TIMED for flag in range(256))  # flags.translate: TIMED where a chunk is timed
BLOCK_BYTES = 1 << 18  # bytes gathered before the engine runs: memory stays flat, calls few
READ_BYTES = 1 << 20  # a pcap read at a time


@dataclass(slots=True)
class Block:
    data: bytes
    starts: array  # int64 stream offsets
    times: array  # int64 ns (0 where untimed)
    flags: bytearray | bytes
    exact: bool = True  # every time is a Stamp (integer ns): the engine can subtract them as Python does
    chunks: list[Chunk | None] = field(default_factory=list)  # the source's, or made on demand

    def chunk(self, index: int) -> Chunk:
        chunk = self.chunks[index] if self.chunks else None
        if chunk is None:
            begin = self.starts[index] - self.starts[0]
            end = self.starts[index + 1] - self.starts[0] if index + 1 < len(self.starts) else len(self.data)
            flag = self.flags[index]
            chunk = Chunk(self.data[begin:end], Stamp(self.times[index]) if flag & TIMED else None,
                          bool(flag & RECORD_END))
        return chunk


class BlockBuilder:
    """Gathers chunks into blocks, carrying the stream offset and the chunk before across them."""

    def __init__(self, timing: LineTiming, streaming: bool = False) -> None:
        self.timing = timing
        # A pipe: each chunk is a block as it comes (a live feed is never held back to fill one).
        self.block_bytes = 1 if streaming else BLOCK_BYTES
        self.streaming = streaming
        self.offset = 0
        self.previous: tuple[int, float | None] | None = None
        self.exact = True  # so far every time is a stamp, all within +-2**62 ns (no difference overflows int64)
        self._reset()

    def _reset(self) -> None:
        self.pieces: list[bytes] = []
        self.kept: list[Chunk | None] = []
        self.starts, self.times, self.flags = array("q"), array("q"), bytearray()
        self.size = 0

    def add(self, chunk: Chunk) -> Iterator[Block]:
        data = chunk.data
        if not data and type(chunk) is not PartChunk:  # (a record of which no byte was captured: a cut all the same)
            return
        time = chunk.time
        flag = RECORD_END if chunk.boundary else 0
        ns = 0
        if time is not None:
            flag |= TIMED
            if isinstance(time, Stamp):
                self._span(time.ns, time.ns)
                ns = time.ns if self.exact else 0
            else:
                self.exact = False
            if self.previous is not None and silence_before(self.previous, self.offset, time, self.timing):
                flag |= SILENCE_BEFORE
        self.previous = (self.offset, time)
        self.pieces.append(data)
        self.kept.append(chunk)
        self.starts.append(self.offset)
        self.times.append(ns)
        self.flags.append(flag)
        self.offset += len(data)
        self.size += len(data)
        if self.size >= self.block_bytes:
            yield from self.flush()

    def _span(self, lowest: int, highest: int) -> None:
        """Times from `lowest` to `highest` ns: the engine subtracts any two within +-2**62 as Stamp.__sub__
        does (_timeline.h stamp_seconds), none further out (int64)."""
        if lowest < -(1 << 62) or highest >= 1 << 62:
            self.exact = False

    def flush(self) -> Iterator[Block]:
        if self.kept:
            yield Block(b"".join(self.pieces), self.starts, self.times, self.flags, self.exact, self.kept)
            self._reset()

    def chunks(self, chunks: Iterable[Chunk]) -> Iterator[Block]:
        for chunk in chunks:
            yield from self.add(chunk)
        yield from self.flush()

    def pcap(self, reader: Any, scan: Any, trail: RecordTrail | None = None) -> Iterator[Block]:
        """The rest of a pcap (sources/pcap.py PcapRecords, standing between two records) in bulk; `trail`
        (sources/trail.py) is told each block's reads before it is given out."""
        from dissector.sources.common import Input

        yield from self.flush()
        inp = reader.inp
        big_endian = reader.order == ">"
        buffer, position = b"", 0
        empties: tuple[bytes, int] | None = None  # the last scan's records, when it passed over empty ones
        while True:
            # (a pipe's bytes as they come; a file's a megabyte at a time)
            data = inp.read_some(READ_BYTES) if self.streaming else inp.read(READ_BYTES)
            buffer = buffer[position:] + data
            position = 0
            previous = self.previous
            if previous is not None:
                time = previous[1]
                if time is not None and not isinstance(time, Stamp):
                    break  # (never from a pcap reader: its times are stamps)
                previous = (previous[0], time.ns if time is not None else 0, time is not None)  # type: ignore[union-attr]
            begun, offset = position, self.offset
            payload, starts, times, flags, position, stop, records, self.offset, last, span = scan(
                buffer, position, big_endian, reader.units, self.offset, previous, self.timing.char_time,
                self.timing.t35, reader.chunk_size,
            )
            numbers = [trail.number_base + number for number in record_numbers(buffer, begun, position, reader)] \
                if trail is not None and trail.numbering else []
            reader.record += records
            if last is not None:
                self.previous = (last[0], Stamp(last[1]) if last[2] else None)
            block = Block(payload, array("q", starts), array("q", times), flags, self.exact)
            if records:
                # The last record's time (PcapRecords.recorded_until: every record's but one at the epoch):
                # the last timed chunk's; where the scan passed over empty records, from its buffer's record
                # headers, read once at the end, or when a later scan passes over more and times none.
                timed = flags.translate(TIMED_ONLY).rfind(TIMED)
                if empties is not None and timed < 0 and records > len(flags):
                    reader.recorded_until = last_record_time(*empties, reader) or reader.recorded_until
                if timed >= 0:
                    reader.recorded_until = Stamp(block.times[timed])
                    empties = None
                if records > len(flags):
                    empties = (buffer, position)
            if span is not None:
                self._span(*span)
            empty: list[tuple[int, int | None]] = []  # (the records it passed over that -w writes again: sources/trail.py)
            if trail is not None and trail.times and records > len(flags):
                empty = empty_records(buffer, begun, position, reader, offset)
            if flags:
                if trail is not None:
                    observe_block(trail, block, empty, numbers)
                yield block
            elif empty and trail is not None:
                trail.observe_reads([], [], self.offset, empty)
            if stop or not data:
                break
        if empties is not None:
            reader.recorded_until = last_record_time(*empties, reader) or reader.recorded_until
        # A record the Python reader must see, or the end (a record cut short: its warning): it reads
        # the rest, from the bytes not scanned.
        rest = reader.records(Input(inp.stream, inp.name, prefix=buffer[position:]))
        yield from self.chunks(rest if trail is None else trail.observe(rest))


def last_record_time(buffer: bytes, end: int, reader: Any) -> Stamp | None:
    """The time of the last timed record of `buffer` up to `end` (pcap records from its start)."""
    header = struct.Struct(reader.order + "IIII")
    position, time = 0, None
    while position + 16 <= end:
        seconds, fraction, captured, _original = header.unpack_from(buffer, position)
        if seconds or fraction:
            time = Stamp.from_parts(seconds, fraction, reader.units)
        position += 16 + captured
    return time


def observe_block(trail: RecordTrail, block: Block, empty: list[tuple[int, int | None]] | None = None,
                  numbers: list[int] | None = None) -> None:
    """A block read in bulk (a pcap's records: no comments) to the trail, as trail.observe takes chunks:
    where each read begins and, for -w, its time (integer ns: a Stamp is made only where an item is cut);
    `numbers`: each read's record number (record_numbers)."""
    times = None
    if trail.times:
        times = [ns if flag & TIMED else None for ns, flag in zip(block.times, block.flags)]
    trail.observe_reads(block.starts, times, block.starts[0] + len(block.data), empty or (), numbers or ())


def record_numbers(buffer: bytes, position: int, end: int, reader: Any) -> list[int]:
    """The record numbers (tshark's frame.number) of the records with bytes among the standard ones of `buffer`
    from `position` to `end` (a bulk scan's reads, one a record: scan_pcap stops before a longer one), the
    `reader` having read its `record` records before them; its empty records are numbered, not read."""
    header = struct.Struct(reader.order + "IIII")
    number, found = reader.record, []
    while position + 16 <= end:
        captured = header.unpack_from(buffer, position)[2]
        number += 1
        if captured:
            found.append(number)
        position += 16 + captured
    return found


def source_blocks(source: Any, timing: LineTiming, builder: BlockBuilder | None = None,
                  trail: RecordTrail | None = None) -> Iterator[Block]:
    """The blocks of a source (sources/reader.py Source): pcap records in bulk, other chunks as they come
    (`builder`: one whose block_bytes its caller sets between blocks, framespath.py's -c N), every chunk
    through `trail` (sources/trail.py: -w's reads, a pcapng's comments) when one is given."""
    from dissector.accel import fastsummary

    builder = builder or BlockBuilder(timing, getattr(source, "streaming", False))
    head, rest = source.parts()
    try:
        bulk = fastsummary.built()
        if bulk and getattr(rest, "between", False) and getattr(rest, "linktype", None) == LINKTYPE_USER0:
            yield from builder.chunks(head if trail is None else trail.observe(head))
            yield from builder.pcap(rest, fastsummary._summary.scan_pcap, trail)
        elif trail is None:
            yield from builder.chunks(head)
            yield from builder.chunks(rest)
        else:  # (one pass of the trail over both: a record may go on from the head into the rest)
            chunks = trail.observe(chain(head, rest))
            yield from builder.chunks(islice(chunks, len(head)))
            yield from builder.chunks(chunks)
    finally:
        source.finished()


def blocks_from_chunks(chunks: Iterable[Chunk], timing: LineTiming,
                       builder: BlockBuilder | None = None) -> Iterator[Block]:
    """Blocks of the chunks a source gives (any source: pcapng, RTAC records, hex dumps...). A source
    observed by a trail (sources/trail.py observed: -w, a pcapng's comments) is read as it would be
    unobserved, its pcap records in bulk too, the trail told of every read before its items are asked for."""
    trail: RecordTrail | None = getattr(chunks, "trail", None)
    source = chunks.source if trail is not None else chunks  # type: ignore[attr-defined]
    sources = getattr(source, "sources", None)
    if sources is not None:  # a ring buffer's files (app/rings.py RingSource): one stream, each read in bulk
        builder = builder or BlockBuilder(timing)
        for each in sources():
            if trail is not None:
                trail.name = each.name  # (its records named by their file)
                trail.number_base = source.packets_before  # (its records numbered on from the files before)
            yield from source_blocks(each, timing, builder, trail)
        return
    if hasattr(source, "parts"):
        yield from source_blocks(source, timing, builder, trail)
        return
    yield from (builder or BlockBuilder(timing)).chunks(chunks)
