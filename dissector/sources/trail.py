"""What a decode keeps of its input's records beside the items (app/cli.py Sinks): the packet comments of
a pcapng's records (sources/common.py NotedChunk) by the bytes they are on, and, for -w, the chunks
(records, reads) its bytes came in.

A frame gets the comments of every record it has bytes in (a record of three frames: each of them), as
-V and --json show them and -w keeps them. A -w copy writes an item whose input's time changes inside it
as the chunks it came in, each a record at its own time (render/capturefile.py write_items): written as
one record at its first byte's time, a frame that had a silence inside it lost that warning. The reader
measures a silence from a chunk's time and length, so the copy's chunks before it must be the input's:
the item is cut at every chunk inside it, and an item from inside a timed chunk has its first record
begin where the chunk begins, the items before it in that chunk in it too (alone, its first record's end
would read later than the chunk's and make a silence up; when they are written already, it is one
record, as before). So a copy of timed reads is its reads: a record beginning inside one, the next frame
or noise run of a tap's read on its own, is a boundary the input did not have, a frame's bound to the
reader, and made a frame of noise the decode found none in, or a request of the noise after a frame (14
of 2,000 random streams of tap reads, tests/differential/test_copy_read_bounds.py). An item without a
time change inside stays one record (a frame a packet, as mbrtu reads it).

The items come in the order of their bytes: what lies before an item asked about is forgotten, so
memory holds the chunks of the items not yet out (and every comment of a summary the engine writes).
"""
from __future__ import annotations

import re
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any

from dissector.model import Chunk, Item, Stamp
from dissector.sources.common import NotedChunk, StoredChunk

# The comments vw3-decode writes on the records of a -w copy (render/capturefile.py noise_comment,
# CaptureOutput.write_items and release, joined by "; "): its decode's own words, which every decode of
# the copy says again. Read back they are no packet comment: a copy of a copy does not say them twice.
# A record captured in part's reason holds "; " itself (framing/stream.py _cut_part: `captured in part (5 of its
# 9 bytes; slave 2, function 3; the answer to #1): its CRC cannot be checked`), the other reasons none.
_OWN_PART = (r"(?:(?:then )?noise: \d+ bytes?, (?:captured in part \([^()]*\): its [CL]RC cannot be checked|(?:(?!; ).)+)"
             r"|then a damaged frame \(\d+ bytes\)|a frame \(\d+ bytes?\))")
_OWN = re.compile(rf"{_OWN_PART}(?:; {_OWN_PART})*")


def own_comment(text: str) -> bool:
    """Is a pcapng comment one vw3-decode writes of its decode (above)?"""
    return _OWN.fullmatch(text) is not None


# A piece of an item: (its end, counted from the item's first byte; its time; the comments of its records;
# where its record begins in the stream: before the item, for a first piece from inside a chunk).
Piece = tuple[int, Any, tuple[str, ...], int]


def _key(time: Any) -> Any:
    return getattr(time, "ns", time)  # (two Stamps 100 ns apart are one float near 1.7e9 s)


class RecordTrail:
    """The trail of one decode's stream (a ring buffer's files are one): `observe` its chunks, then ask
    `pieces` of each item, in order. `times`: keep where the time changes (-w)."""

    def __init__(self, times: bool, numbering: Callable[[Chunk], int | None] | None = None) -> None:
        self.times = times
        # The record number (tshark's frame.number) of the chunk observed (sources/reader.py Source.packet_number):
        # where each record with bytes begins, (stream offset, number), for record_of (-T fields' `record`).
        self.numbering = numbering
        self._numbers: deque[tuple[int, int | None]] = deque()
        self.number_base = 0  # the records of a ring's files before the one read in bulk (accel/records.py)
        self.offset = 0  # bytes observed: the next chunk's offset, as the framers count
        self._parts: deque[tuple[int, Any]] = deque()  # (first byte, time) of each chunk (-w)
        self._commented: deque[tuple[int, int, tuple[str, ...]]] = deque()  # (first byte, end, comments)
        self._empty: deque[tuple[int, Any, tuple[str, ...]]] = deque()  # (offset, time, comments): -w's empty records
        # (first byte, end, record's time) of each chunk decoded untimed whose record has a time (common.py
        # StoredChunk): -w writes the items there rather than at the epoch
        self._stored: deque[tuple[int, int, Any]] = deque()
        self.comments = 0  # comments read
        self.name: str | None = None  # the file being read, of a ring buffer's (None: the input's one)
        # (file, record, comments) of each record carrying comments
        self.records: list[tuple[str | None, int, int]] = []

    def observe(self, chunks: Iterable[Chunk]) -> Iterator[Chunk]:
        times, parts = self.times, self._parts
        offset = start = self.offset  # (the record being read starts at `start`)
        numbering = self.numbering
        for chunk in chunks:
            number = numbering(chunk) if numbering is not None else None  # (every chunk's, in order: Source.number_of)
            if not chunk.data and type(chunk) in (Chunk, NotedChunk):  # (an empty record: common.py record_chunks)
                if times:
                    self._empty.append((offset, chunk.time, getattr(chunk, "comments", ())))
                start = offset
                yield chunk
                continue
            if numbering is not None and offset == start:  # (a record's first bytes)
                self._numbers.append((offset, number))
            if times:
                parts.append((offset, chunk.time))
                if type(chunk) is StoredChunk and chunk.stored is not None:
                    self._stored.append((offset, offset + len(chunk.data), chunk.stored))
            offset += len(chunk.data)
            if isinstance(chunk, NotedChunk) and chunk.comments:  # (a PartChunk is one, with comments or none)
                self._commented.append((start, offset, chunk.comments))
                self.comments += len(chunk.comments)
                self.records.append((self.name, chunk.record, len(chunk.comments)))
            if chunk.boundary:
                start = offset
            self.offset = offset
            yield chunk

    def observe_reads(self, starts: Sequence[int], times: list[int | None] | None, end: int,
                      empty: Sequence[tuple[int, int | None]] = (), numbers: Sequence[int] = ()) -> None:
        """Reads taken in bulk, which carry no comments (a pcap's records, accel/records.py observe_block),
        as `observe` takes them: where each begins, its time in integer ns (-w), the end of the last; `empty`:
        the empty records among them, (offset, time in ns or None); `numbers`: each read's record number (when
        numbering)."""
        if self.numbering is not None:
            self._numbers.extend(zip(starts, numbers))
        if self.times and times is not None:
            self._parts.extend(zip(starts, times))
            self._empty.extend((offset, None if ns is None else Stamp(ns), ()) for offset, ns in empty)
        self.offset = end

    def record_of(self, item: Item) -> int | None:
        """The record number (tshark's frame.number) of the record holding the item's last byte, where Wireshark
        shows it (the plugin shows a frame split over records in the record that completes it, and its
        request_frame and response_frame name that one); None where the input numbers no record. Asked of the
        items in order: what lies before is forgotten."""
        numbers, last = self._numbers, item.offset + max(len(item.raw), 1) - 1
        while len(numbers) > 1 and numbers[1][0] <= last:
            numbers.popleft()
        return numbers[0][1] if numbers and numbers[0][0] <= last else None

    @property
    def idle(self) -> bool:
        """Nothing to tell of any item yet: no times kept, no comment read."""
        return not self.times and not self._commented

    def split(self, items: list[Item]) -> dict[int, list[Piece]]:
        """The pieces of the items (heard, in order) that are not one record without comments, by id(item):
        `pieces` of each, but of an item within one chunk when no comment is kept (the usual) at once."""
        found = {}
        parts, commented = self._parts, self._commented
        for item in items:
            start = item.offset
            while len(parts) > 1 and parts[1][0] <= start:
                parts.popleft()
            if not commented and (len(parts) < 2 or parts[1][0] >= start + len(item.raw)) \
                    and not _inside(item, parts) and not (self._empty and self._empty[0][0] <= start + len(item.raw)) \
                    and not (self._stored and self._stored[0][0] < start + len(item.raw)):
                continue
            pieces = self.pieces(item)
            if pieces is not None:
                found[id(item)] = pieces
        return found

    def settled(self, offset: int) -> int:
        """Where the chunk holding byte `offset` begins (of those observed; `offset` past them): no item
        from `offset` on begins its first record before it (the module's docstring)."""
        begin = offset
        for first, _time in self._parts:
            if first > offset:
                break
            begin = first
        return begin

    def pieces(self, item: Item) -> list[Piece] | None:
        """The item's pieces, the first at the item's time; None for one piece without comments. An empty
        record read after one of its bytes (before its first: the input's first) is a piece of no byte there."""
        found = self._stored_times(item, self._pieces(item))
        empty = self._empty
        end = item.offset + len(item.raw)
        if not empty or empty[0][0] > end:
            return found
        split = found or [(item.length, item.time, (), item.offset)]
        while empty and empty[0][0] <= end:
            offset, time, comments = empty.popleft()
            at = max(offset - item.offset, 0)
            ended = [index for index, piece in enumerate(split) if piece[0] == at]
            if ended or at == 0:
                index = ended[-1] + 1 if ended else 0
            else:  # (inside a piece: it is cut there, its second part at the time of the read after)
                index = next(index for index, piece in enumerate(split) if piece[0] > at)
                stop, was, texts, first = split[index]
                after = next((when for begin, when in reversed(self._parts) if begin <= offset), was)
                after = Stamp(after) if type(after) is int else after
                split[index:index + 1] = [(at, was, texts, first), (stop, after, (), offset)]
                index += 1
            split.insert(index, (at, time, comments, max(offset, item.offset)))
        return split

    def _stored_times(self, item: Item, found: list[Piece] | None) -> list[Piece] | None:
        """`found` with each untimed piece that begins in a chunk of a StoredChunk at that chunk's record time."""
        stored, start = self._stored, item.offset
        while stored and stored[0][1] <= start:
            stored.popleft()
        if not stored or stored[0][0] >= start + len(item.raw):
            return found
        pieces = found or [(item.length, item.time, (), item.offset)]
        timed = []
        for index, (end, time, comments, first) in enumerate(pieces):
            begin = start + (pieces[index - 1][0] if index else 0)
            record = next((at for low, high, at in stored if low <= begin < high), None)
            timed.append((end, record if time is None and record is not None else time, comments, first))
        return timed

    def _pieces(self, item: Item) -> list[Piece] | None:
        start = item.offset
        end = start + len(item.raw)
        parts, commented = self._parts, self._commented
        while len(parts) > 1 and parts[1][0] <= start:
            parts.popleft()
        while commented and commented[0][1] <= start:
            commented.popleft()
        inside = _inside(item, parts)
        if (len(parts) < 2 or parts[1][0] >= end) and not (commented and commented[0][0] < end) and not inside:
            return None  # (within one chunk, no comment: the usual)
        cuts: list[tuple[int, Any]] = []
        anchor = start  # where its first record must begin: the chunk's start (the module's docstring)
        if parts and parts[0][0] <= start:
            anchor = parts[0][0]
            keys = {_key(parts[0][1])}
            for first, time in parts:
                if first >= end:
                    break
                if first > start:
                    # (a read taken in bulk keeps its time in integer ns: observe_reads)
                    cuts.append((first - start, Stamp(time) if type(time) is int else time))
                    keys.add(_key(time))
            keys.discard(None)
            if len(keys) < 2:  # (no time changes inside: one record, a frame a packet)
                cuts, anchor = [], anchor if inside else start
        if not cuts and not (commented and commented[0][0] < end) and not inside:
            return None
        bounds = [(0, item.time), *cuts, (item.length, None)]
        pieces: list[Piece] = []
        for (begin, time), (stop, _next) in zip(bounds, bounds[1:]):
            comments: list[str] = []
            for first, last, texts in commented:
                if first >= start + stop:
                    break
                if last > start + begin:
                    comments += texts
            pieces.append((stop, time, tuple(comments), start + begin if begin else anchor))
        return pieces


def _inside(item: Item, parts: deque[tuple[int, Any]]) -> bool:
    """Does the item begin inside a timed chunk (`parts` from the one holding its first byte)? Then its
    first record begins where the chunk does (the module's docstring)."""
    return bool(parts) and parts[0][0] < item.offset and parts[0][1] is not None


def item_comments(pieces: list[Piece] | None) -> list[str]:
    """The comments of an item of these pieces, in the order of its records."""
    return [text for _end, _time, comments, _start in pieces or () for text in comments]


def observed(source: Any, trail: RecordTrail) -> Any:
    """`source` (sources/reader.py Source, app/rings.py RingSource) with its chunks through the trail. The
    compiled paths read what it wraps as they read a source (accel/records.py blocks_from_chunks: a pcap's
    records in bulk, telling the trail of each block's reads, observe_reads)."""
    return _Observed(source, trail)


class _Observed:
    def __init__(self, source: Any, trail: RecordTrail) -> None:
        self.source = source
        self.trail = trail
        self.streaming = getattr(source, "streaming", False)

    def __iter__(self) -> Iterator[Chunk]:
        sources = getattr(self.source, "sources", None)
        if sources is None:
            return self.trail.observe(self.source)
        return self._files(sources())

    def _files(self, sources: Iterable[Any]) -> Iterator[Chunk]:
        """A ring buffer's files (app/rings.py RingSource) one after the other: each names its records."""
        for source in sources:
            self.trail.name = source.name
            yield from self.trail.observe(source)
