"""The compiled summary path for timed captures: pcap and pcapng records with their times.

A pcap went through the Python stages record by record (about 20 us a frame); here the records come in
blocks (dissector/accel/records.py: the bytes of many records at once, with arrays of where each starts,
its time and its flags) and the engine (_summary.c run_timed, _timeline.h, _timedframe.h) does for them
what the Python stages do with the same chunks: the framer's decision with the bytes it has when it first
looks at a frame (a record's end is evidence), times and response times, the time column (-t r, d, dd),
the pairing timeout, and silences inside a frame. What it does not show it hands over, as the untimed
path does (fastsummary.py), at a frame start: the Python stages take the stream there, inside its chunk
(the framer and the gap checker are told where that chunk started and when: StreamFramer.take_over,
GapChecker.take_over), are fed the following chunks as they would have been, and give the stream back
at their next idle point. tests/differential/test_timed_summary.py holds both paths byte-identical.
"""
from __future__ import annotations

from array import array
from bisect import bisect_right
from collections.abc import Callable, Iterable
from typing import Any

from dissector.accel.fastsummary import NEED, PythonSide, built, forget_changed, make_engine
from dissector.accel.records import Block
from dissector.model import Chunk, Item, Stamp
from dissector.sources.common import PartChunk
from dissector.pipeline import Dissector
from dissector.render.pcapwriter import NANOS
from dissector.render.timefmt import Clock, FirstPacket, network

CLOCKS = {"r": 0, "d": 1, "dd": 1}  # the time columns the engine writes (timefmt.Clock.text)
# -t d of a capture whose time column counts its packets (timefmt.Clock.packets: a network or several-interface
# capture's): from the packet captured before each item's first, which the engine is told per chunk (befores).
PACKET_DELTAS = 2
NO_BEFORE = -(1 << 63)  # _timeline.h NO_BEFORE: the chunk's packet is the capture's first


def usable(clock: Clock) -> bool:
    """The engine writes this time column, and is built from these sources."""
    return clock.format in CLOCKS and not clock.deltas and built()


class TimedPath:
    """Drives a timed stream through the engine and, where it hands over, the Python stages."""

    def __init__(self, dissector: Dissector, annotator: Any | None, clock: Clock,
                 write_items: Callable[[list[Item]], None], write_lines: Callable[[bytes], None],
                 timeout: float | None, shown: bool = True) -> None:
        self.dissector = dissector
        self.framer = dissector.framer
        self.pairer = dissector.pairer
        self.annotator = annotator
        self.clock = clock
        # (shown False: its lines are only counted, --stats)
        self.engine = make_engine(annotator, shown, self.pairer)
        timing = self.framer.timing
        # A capture counting its packets (timefmt.Clock.packets): -t r from its first packet, given the engine as
        # its first reference; -t d from the packet before each item's (self.befores); -t dd as any capture's.
        self.packets = clock.packets
        self.befores: array | None = None
        self.marked: bool | None = None  # the bus's chunks are marked in `packets`
        mode = CLOCKS[clock.format]
        if self.packets is not None and clock.format == "d":
            mode, self.befores = PACKET_DELTAS, array("q")
        self.engine.set_timing(timing.char_time, timing.max_silence, timeout, mode)
        self.engine.clock_nanos = int(clock.units == NANOS)  # (a nanosecond capture's 9 decimals: timefmt.py)
        self.write_items = write_items
        self.side = PythonSide(dissector, write_items)  # the Python stages' steps over the stream
        self.write_lines = write_lines
        # The chunks not consumed yet: buf holds their bytes from stream offset `base` (inside chunk 0).
        self.buf = b""
        self.base = 0
        self.pos = 0  # the next byte neither side has taken, buf[pos]
        self.starts = array("q")
        self.times = array("q")
        self.flags = bytearray()
        self.chunks: list[Chunk | None] = []  # made when the Python stages need them,
        self.owners: list[Block] = []  # by the block each came in
        self.local = array("q")  # and its index there
        self.python = False  # the Python stages have the stream
        self.taken_at = 0
        self.fed = 0  # chunks given to the Python stages (an index into the lists above)
        self.engine_ok = True  # False: a source whose times the engine cannot subtract (plain floats)
        # The end of the last record captured in part given (a cut the engine does not make: StreamFramer
        # _cut_part): the Python stages take the stream before it and give it back once past it.
        self.cut_until = 0
        self.on_hand_back: Callable[[], None] | None = None  # called as the engine takes the stream back
        self.sync_clock = True  # the engine writes the time column: the clock's references go with the stream
        self.numbered = 0  # items numbered before the engine's last run
        self.report: Any | None = None  # a compiled Report the engine feeds (reportfeed.py): synced around runs
        self._judge: bytes | None = None

    # -- input ------------------------------------------------------------------------------------
    def feed(self, block: Block) -> None:
        if not len(block.starts):
            return
        self._trim()
        if not self.starts:
            self.base = block.starts[0]
        self.buf += block.data
        self.starts.extend(block.starts)
        self.times.extend(block.times)
        self.flags += block.flags
        if self.packets is not None:
            self._packet_refs(block)
        count = len(block.starts)
        self.chunks.extend([None] * count)
        self.owners.extend([block] * count)
        self.local.extend(range(count))
        self.engine_ok = self.engine_ok and block.exact
        for index, chunk in enumerate(block.chunks):  # (none where the engine read the records in bulk)
            if type(chunk) is PartChunk:  # (+1 for one of no byte: the engine has not passed it at its start)
                self.cut_until = block.starts[index] + max(len(chunk.data), 1)
        if (not self.engine_ok or self.cut_until > self.base + self.pos) and not self.python:
            self._hand_over()
        while self._python_frames() if self.python else self._engine_frames():
            pass  # one side gave the stream to the other: go on there

    def finish(self) -> None:
        if not self.python:
            self._hand_over()
        self.framer.pause_at(None)
        items: list[Item] = []
        while self.fed < len(self.starts):
            items += self.dissector.feed(self._chunk(self.fed))
            self.fed += 1
        self.write_items(items + self.dissector.finish())

    # -- the engine's side --------------------------------------------------------------------------
    def _engine_frames(self) -> bool:
        """The engine's lines up to where it needs more bytes (False) or hands the stream over (True)."""
        self.numbered = self.engine.count
        engine = self.engine
        if self.marked and not engine.has_first and self.packets.start is not None:
            # (-t r: Clock.observe's first, the capture's first packet, once a bus's chunk is marked)
            engine.has_first, engine.first_ns = True, self.packets.start
        report = self.report
        if report is not None:
            report.pull()
        if self.befores is None:
            lines, self.pos, status = self.engine.run_timed(self.buf, self.pos, self.base, self.starts, self.times,
                                                            self.flags)
        else:
            lines, self.pos, status = self.engine.run_timed(self.buf, self.pos, self.base, self.starts, self.times,
                                                            self.flags, self.befores)
        if report is not None:
            report.push()
        if lines:
            self.write_lines(lines)
        if status == NEED:
            return False
        self._hand_over()
        return True

    def _hand_over(self) -> None:
        """The Python stages take the stream at buf[pos], inside its chunk."""
        offset = self.base + self.pos
        self.taken_at = offset
        self.python = True
        self.side.take(self.engine.count)
        if not self.starts:
            self.framer.restart_at(offset, self.engine.expect)
            return
        index = self._chunk_of(offset)
        while index > 0 and self.starts[index - 1] == offset:
            index -= 1  # (a record captured in part of no byte at offset: fed next, below)
        chunk = self._chunk(index)
        start = self.starts[index]
        self.framer.restart_at(offset, self.engine.expect)
        if offset < start + len(chunk.data):
            self.framer.take_over(offset, self.engine.expect, start, chunk)
        if self.dissector.gaps is not None:
            self.dissector.gaps.take_over(start, chunk)
        self.fed = index if start == offset and not chunk.data else index + 1
        self.pairer.count = self.engine.count
        # The framer looks at `offset` first with every chunk it had when it took the frame before (it
        # may have waited for more): give them before it frames anything.
        decided = self.engine.decided
        if self.fed < len(self.starts) and self.starts[self.fed] < decided:
            self.framer.pause_at(offset)
            while self.fed < len(self.starts) and self.starts[self.fed] < decided:
                items = self.dissector.feed(self._chunk(self.fed))  # (none: paused)
                self.fed += 1
                if items:
                    self.write_items(items)
        if self.sync_clock:
            first, previous = self.engine.clock
            clock = self.clock
            clock.first = None if first is None else (FirstPacket if self.marked else Stamp)(first)
            clock._previous_captured = clock._previous_shown = None if previous is None else Stamp(previous)

    # -- the Python stages' side --------------------------------------------------------------------
    def _python_frames(self) -> bool:
        """The Python stages' items up to where they need more chunks (False) or give the stream back
        to the engine (True)."""
        framer = self.framer
        if not self.engine_ok:
            # The engine will not take the stream back: the Python stages frame freely, chunk by chunk.
            framer.pause_at(None)
            while self.fed < len(self.starts):
                items = self.dissector.feed(self._chunk(self.fed))
                self.fed += 1
                if items:
                    self.write_items(items)
            return False
        side = self.side
        while True:
            if side.ready() and framer.offset > self.taken_at and self.pairer.idle and framer.offset >= self.cut_until:
                self._forget_changed()
                offset, rest, expect = framer.hand_back()
                self.pos = offset - self.base
                self.engine.count = self.pairer.count
                side.give(self.pairer.count)
                self.engine.expect = expect
                self.engine.glitchy = framer.glitchy
                self.engine.decided = offset + len(rest)  # where the framer's buffer ended: what it has seen
                clock = self.clock
                previous = clock._previous_shown if clock.format == "dd" else clock._previous_captured
                if not (_exact(clock.first) and _exact(previous)):
                    self.engine_ok = False
                    continue
                self.engine.clock = (_ns(clock.first), _ns(previous))
                if self.on_hand_back is not None:
                    self.on_hand_back()
                self.python = False
                return True
            if side.step():
                continue
            if self.fed >= len(self.starts):
                return False  # it needs chunks that have not come yet
            items = self.dissector.feed(self._chunk(self.fed))
            self.fed += 1
            side.write(items)

    def _forget_changed(self) -> None:
        if self._judge is not None and self.pairer.listen_changed:
            self.judge = self._judge  # (with the slaves in Listen Only Mode now)
        forget_changed(self.engine, self.annotator, self.pairer)

    @property
    def judge(self) -> bytes | None:
        """Judge mode (_judge.h): a bit per (slave, function code) whose transactions the Python stages take;
        None: not in it. The engine's bitmap adds every code of the slaves in Listen Only Mode (pairing.py
        in_listen_only), whose mode it does not keep."""
        return self._judge

    @judge.setter
    def judge(self, rows: bytes | None) -> None:
        self._judge = rows
        listening = self.pairer.listen_only_slaves() if rows is not None else None
        if listening:
            marked = bytearray(rows)  # type: ignore[arg-type]
            for slave in listening:
                marked[slave * 32 : slave * 32 + 32] = b"\xff" * 32
            rows = bytes(marked)
        self.engine.judge = rows

    # -- the chunks kept ------------------------------------------------------------------------------
    def _chunk_of(self, offset: int) -> int:
        """The chunk holding stream offset `offset`: the last one starting at or before it."""
        return max(0, bisect_right(self.starts, offset) - 1)

    def _chunk(self, index: int) -> Chunk:
        chunk = self.chunks[index]
        if chunk is None:
            chunk = self.chunks[index] = self.owners[index].chunk(self.local[index])
        return chunk

    def _trim(self) -> None:
        """Forget the chunks both sides are done with (memory stays flat)."""
        if not self.starts:
            return
        keep_from = self.base + self.pos if not self.python else self.framer.offset
        index = self._chunk_of(keep_from)
        if self.python:
            index = min(index, self.fed)
        if index <= 0:
            return
        start = self.starts[index] if index < len(self.starts) else self.base + len(self.buf)
        self.buf = self.buf[start - self.base :]
        self.pos -= start - self.base
        self.base = start
        del self.starts[:index]
        del self.times[:index]
        del self.flags[:index]
        del self.chunks[:index]
        del self.owners[:index]
        del self.local[:index]
        if self.befores is not None:
            del self.befores[:index]
        self.fed -= index
        if self.marked and not self.python:
            # (the engine has the stream: no item before the chunk kept will ask its packet's time, the marks stay
            # few; the Python stages' pairer may hold a request from before it, their Sinks forget as they show)
            self.packets.forget(start)

    def _packet_refs(self, block: Block) -> None:
        """The references of a capture counting its packets (timefmt.Clock.observe with packets), for the block's
        chunks: the first packet's time as the engine's first (-t r), the packet before each chunk's first byte
        (-t d), read from the marks the reader made as it gave them (sources/ethernet.py PacketTimes). The
        engine does not take the stream where the Python stages' reference would differ: a chunk holding a
        mark past its first byte (another packet's bytes: an item starting there counts from that one), or a
        bus whose chunks are marked, then not (timefmt.network)."""
        packets = self.packets
        marked = network(packets) is not None
        if self.marked is None:
            self.marked = marked
        if marked != self.marked:
            self.engine_ok = False
        if not marked:
            if self.befores is not None:
                self.befores.extend([NO_BEFORE] * len(block.starts))
            return
        if self.befores is None:
            return
        offsets, befores = packets.offsets, packets.befores
        starts = block.starts
        last = len(offsets) - 1
        mark = bisect_right(offsets, starts[0]) - 1
        ends = starts[1:]
        ends.append(starts[0] + len(block.data))
        out = self.befores
        for start, end in zip(starts, ends):
            while mark < last and offsets[mark + 1] <= start:
                mark += 1
            if mark < last and offsets[mark + 1] < end:
                self.engine_ok = False  # (a mark inside the chunk)
            before = befores[mark] if mark >= 0 else None
            out.append(NO_BEFORE if before is None else before)


def _exact(time: float | None) -> bool:
    return time is None or isinstance(time, Stamp)


def _ns(time: float | None) -> int | None:
    return None if time is None else time.ns  # type: ignore[union-attr]


def summarize_timed(blocks: Iterable[Block], path: TimedPath, after_block: Callable[[], None]) -> None:
    for block in blocks:
        path.feed(block)
        after_block()
    path.finish()
    after_block()


def summarize_input(chunks: Iterable[Chunk], dissector: Dissector, sinks: Any, annotate: Any | None,
                    warn: Callable[[], None]) -> bool:
    """The plain summary of a timed input (app/cli.py Sinks) through the engine; False (nothing read)
    when it cannot write it: no extension, VW3_PURE_PYTHON, a time column it does not write."""
    from dissector.accel import fastsummary
    from dissector.accel.records import blocks_from_chunks

    if not fastsummary.available() or not usable(sinks.clock):
        return False

    def counted(data: bytes) -> None:
        sinks.valid_frames += 1  # the engine shows valid transactions only
        sinks.output.write_encoded(data)

    path = TimedPath(dissector, annotate, sinks.clock, sinks.accept, counted, dissector.pairer.timeout)
    summarize_timed(blocks_from_chunks(chunks, dissector.framer.timing), path, warn)
    return True


def count_input(chunks: Iterable[Chunk], dissector: Dissector, sinks: Any, annotate: Any | None,
                warn: Callable[[], None]) -> bool:
    """--stats (and --report) of a timed input (app/cli.py Sinks) counted by the engine in the compiled
    store, with the times, the poll intervals and the bus timing (dissector/accel/_bus.h), and what the
    report takes of them (reportfeed.py); the Python stages count what the engine hands over into the
    same store and report. False (nothing read) when it cannot: no extension, VW3_PURE_PYTHON, or what
    was counted before cannot go into the store."""
    from dissector.accel import fastsummary
    from dissector.accel.records import blocks_from_chunks

    if not fastsummary.available() or not built():
        return False
    store = sinks.stats.engine_store(sinks.bus)
    if store is None:
        return False
    frames = store.frames
    path = TimedPath(dissector, annotate, Clock(), sinks.accept, _drop, dissector.pairer.timeout,
                     shown=sinks.report is not None)  # (the report's events read the lines' texts)
    path.sync_clock = False  # (its lines are not shown: the time column is not the sinks')
    path.engine.stats = store
    if sinks.report is not None:
        from dissector.accel.reportfeed import engine_report

        path.report = store.report = engine_report(sinks.report.collector, sinks.health, annotate)
    try:
        summarize_timed(blocks_from_chunks(chunks, dissector.framer.timing), path, warn)
        if path.report is not None:
            path.report.push(True)  # the counts kept in the engine (sums) into the collector and health
    finally:
        store.report = None  # (it holds the collector, whose history holds the store)
    sinks.valid_frames += store.frames - frames
    return True


def _drop(lines: bytes) -> None:
    """The summary lines of --stats' compiled path: only its counts are shown."""
