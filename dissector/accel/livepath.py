"""The compiled path for live capture: the reads of a serial port, with their read times, framed,
paired and shown by the engine, as the pcap path does (timedpath.py), with the Python stages as the
reference and the fallback.

The Python live path (app/live_capture.py, app/live.py) frames each read in the capture thread and
decides, from what its framer holds, when to close a frame after a silence (CaptureThread.flush_due)
and before which time no frame is still to come (safe_time: a request past its --timeout is then shown
unanswered). Here the capture thread only reads, stamps and writes --raw, and hands the reads on
(`framer=None`); the display feeds them to a TimedPath, many reads in one block, each byte at its
arrival (sources/serial_times.py, as the capture thread's framer times them): a read's runs of bytes
with one time are the block's chunks (_ReadBlocks: their arrays made at once, not a Chunk a byte),
and it takes the same decisions at the same reads:

- while the engine has the stream, the Python framer would hold nothing the engine has shown, and a
  request it holds is at the engine's position: so a silence closes nothing and no request expires
  unless the engine holds bytes; when it does and the silence is long enough for a flush, or the
  held bytes are older than --timeout, the Python stages take the stream (TimedPath._hand_over: their
  framer is then the one the Python live path would have) and decide as it does;
- while the Python stages have the stream, their framer and pairer decide, as in the Python live path,
  and give it back at an idle point.

Reads are put in one block as long as no request could expire between them (the last read is within
--timeout of the oldest byte held); lines are shown as soon as the engine or the Python stages give
them, which is when the Python live path shows them.

With -c N (`count`), the Python live path's capture thread keeps its framer's items up to the Nth frame
and stops (CaptureThread.deliver); the display then finishes the pairer, so a request that is the Nth
frame is not known to be answered or not, "the capture ends" before its answer (pairing.capture_ended).
Here the engine's frames of each slice are cut at the Nth before they are decoded and annotated (a request that is the Nth is finished as the
pairer would finish it), and the Python stages' framer, when they have the stream, is cut as the
capture thread cuts it (_CountedFramer); nothing is read after the cut, and finish() then finishes
only the pairer (the capture thread does not finish its framer after a count). tests/differential/test_live_compiled.py holds
the outputs byte-identical to VW3_PURE_PYTHON=1 on the same reads (a tape of them: live_capture.Tape).
"""
from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from typing import Any

from dissector.accel import fastsummary
from dissector.accel.records import SILENCE_BEFORE, TIMED, Block, BlockBuilder
from dissector.accel.timedpath import CLOCKS, TimedPath, usable
from dissector.model import Chunk, Frame, Item, Kind, Stamp, up_to_items
from dissector.decode.pairing import capture_ended
from dissector.framing.timing import may_pause, silence_before
from dissector.pipeline import Dissector
from dissector.render.timefmt import Clock
from dissector.sources.serial_times import ByteTimes, ReadClock

NO_SILENCE_CHECK = 1e300  # live has no GapChecker: a silence inside a frame is no warning, no handover
Read = tuple[bytes, Stamp, float]  # (bytes, stamp, monotonic time): one read of the port


def available() -> bool:
    """The engine is built from these sources and VW3_PURE_PYTHON is not set."""
    return fastsummary.available() and fastsummary.built()


def summary_usable(clock: Clock) -> bool:
    """The engine writes this time column itself (-t r, d, dd)."""
    return usable(clock)


class LivePath:
    """The reads of a live capture through the engine and, where it hands over, the Python stages.

    `summary`: the engine writes the plain summary lines (`write_lines`, UTF-8 bytes) and the Python
    stages the items it hands over (`write_items`); otherwise the engine's clean transactions become
    the Python stages' Frame objects (framespath.py) and every item goes to `write_items`."""

    def __init__(self, dissector: Dissector, annotate: Any | None, clock: Clock | None,
                 write_items: Callable[[list[Item]], None], write_lines: Callable[[bytes], None],
                 timeout: float | None, silence: float, silence_long: float, summary: bool,
                 count: int | None = None, char_time: float | None = None) -> None:
        self.dissector = dissector
        self.left = count  # -c: items still to show (None: no count)
        self.done = False  # -c reached: nothing more is read or shown
        self.cut_time: Stamp | None = None  # -c: the Nth item's time, where the capture stops
        if count is not None:
            assert not summary, "-c: the Python stages show the engine's frames"
            dissector.framer = _CountedFramer(dissector.framer, self)  # type: ignore[assignment]
        self.framer = dissector.framer
        self.timeout = timeout
        self.silence = silence
        self.silence_long = silence_long
        self.engine_items = 0  # frames the engine framed (a line or a Frame each)
        self.python_items = 0  # items the Python stages made
        self._write_items = write_items
        if summary:
            assert clock is not None
            path = TimedPath(dissector, annotate, clock, self._items, self._lines(write_lines), timeout)
            clock_code = CLOCKS[clock.format]
        else:
            from dissector.accel.framespath import _NOTHING, _Frames

            path = TimedPath(dissector, None, Clock(), self._items, lambda records: None, timeout)
            path.sync_clock = False  # (the display's clock sees every item)
            path.judge = _NOTHING
            path.engine.frames = True
            path.write_lines = frames = _Frames(path, annotate, self._engine_frames)
            if count is not None:
                frames.cut = self._cut_engine
            clock_code = 0
        path.side.frame_noise = False  # (fastsummary.PythonSide: live, noise by strides)
        timing = self.framer.timing
        path.engine.set_timing(timing.char_time, NO_SILENCE_CHECK, timeout, clock_code)
        self.path = path
        self.builder = _ReadBlocks(timing)
        # Each byte's arrival, as the capture thread's framer is fed (sources/serial_times.py).
        self.clock = ReadClock(char_time if char_time is not None else timing.char_time)
        self._last_data = 0.0
        self._pending = False  # bytes fed since the last flush (CaptureThread._pending)
        self._tried = False  # a flush tried during this silence (CaptureThread._tried)

    # -- what comes out -----------------------------------------------------------------------------
    def _items(self, items: list[Item]) -> None:
        if items:
            self.python_items += len(items)
            self._write_items(items)

    def _engine_frames(self, items: list[Item]) -> None:
        self.engine_items += len(items)
        self._write_items(items)

    def _lines(self, write: Callable[[bytes], None]) -> Callable[[bytes], None]:
        def lines(data: bytes) -> None:
            self.engine_items += data.count(b"\n")
            write(data)
        return lines

    # -- -c N ---------------------------------------------------------------------------------------------
    def _cut_engine(self, frames: list[Item]) -> list[Item]:
        """The engine's frames of a slice up to the Nth item; a request that is the Nth is finished as
        Pairer.finish finishes the request it awaits an answer for when the capture ends."""
        left = self.left
        assert left is not None
        if len(frames) < left:
            self.left = left - len(frames)
            return frames
        frames = frames[:left]
        self.left, self.done = 0, True
        self._stop_at(frames)
        if frames and frames[-1].kind is Kind.REQUEST:  # its answer (or the frame that told) is past the cut
            last: Frame = frames[-1]  # type: ignore[assignment]
            last.response_ref = None
            capture_ended(last)
        return frames

    def _cut_framed(self, items: list[Item]) -> list[Item]:
        """The Python framer's items up to the Nth frame, as CaptureThread.deliver keeps them."""
        assert self.left is not None
        kept, self.left = up_to_items(items, self.left)
        if self.left <= 0:
            self.done = True
            self._stop_at(kept)
        return kept

    def _stop_at(self, kept: list[Item]) -> None:
        """-c reached: the capture ends at its Nth item (kept's last), live as in its -w file (whose
        closing record is there: live_capture.CaptureThread.stopped_at), even where the cut comes as
        the pairer finishes."""
        if kept:
            self.cut_time = self.dissector.pairer.end = kept[-1].time  # type: ignore[assignment]

    # -- what goes in --------------------------------------------------------------------------------
    def feed(self, reads: Sequence[Read]) -> None:
        """Reads in the order the capture made them (a read with no bytes: the port was silent)."""
        index, count = 0, len(reads)
        while index < count and not self.done:
            data, stamp, now = reads[index]
            if not data:
                self._idle(stamp, now)
                index += 1
                continue
            end = index + 1
            while end < count and reads[end][0]:
                end += 1
            self._reads(reads[index:end])
            index = end

    def finish(self) -> None:
        if self.done:  # -c reached: the pairer finishes what it holds (the framer gives nothing more)
            self._items(self.dissector.finish())
            return
        self.path.finish()

    # -- the capture loop's decisions (live_capture.CaptureThread.step) ---------------------------------
    def _reads(self, reads: Sequence[Read]) -> None:
        path = self.path
        if not path.python and self._within_timeout(reads[0][1], reads[-1][1]):
            # No request can expire between these reads: one block, one pass of the engine.
            for data, stamp, _now in reads:
                self._add(data, stamp)
            self._feed_block()
            last = reads[-1]
            self._last_data, self._pending, self._tried = last[2], True, False
            self._expire(last[1])
            return
        for data, stamp, now in reads:
            self._add(data, stamp)
            self._feed_block()
            self._last_data, self._pending, self._tried = now, True, False
            self._expire(stamp)
            if self.done:
                return

    def _within_timeout(self, first: Stamp, last: Stamp) -> bool:
        if self.timeout is None:
            return True
        held = self._held_time()
        oldest = first if held is None else held
        return last - oldest <= self.timeout

    def _add(self, data: bytes, stamp: Stamp) -> None:
        times = self.clock.byte_times(data, stamp)
        assert times is not None
        for block in self.builder.add_read(data, times, self.clock) or ():
            self.path.feed(block)

    def _feed_block(self) -> None:
        for block in self.builder.flush():
            self.path.feed(block)

    def _idle(self, stamp: Stamp, now: float) -> None:
        self.clock.chunks(b"", stamp)
        stamp = self.clock.promise(stamp)  # (the capture thread's safe time after a read that timed out)
        if self.done:
            return
        if not self._pending:
            self._expire(stamp)
            return
        silent = now - self._last_data
        if self._flush_due(silent):
            self._pending = False
            self._flush()
            self._expire(stamp, safe=stamp)
        else:
            self._expire(stamp)
        self._tried = self._tried or silent >= self.silence

    def _flush_due(self, silent: float) -> bool:
        """CaptureThread.flush_due on the Python framer the Python live path would have."""
        if silent >= self.silence_long:
            return True
        if self._tried or silent < self.silence:
            return False
        if not self._to_python():
            return False  # it would hold nothing: a flush closes nothing
        trial = copy.deepcopy(self.framer)
        trial.pause_at(None)
        return any(isinstance(item, Frame) and item.crc_ok for item in trial.finish(silence=True))

    def _flush(self) -> None:
        """Close what the Python framer would hold (Dissector.flush_idle)."""
        if self.done or not self._to_python():
            return  # nothing held: nothing to close
        self.framer.pause_at(None)
        # (Dissector.flush_idle, but what the framer closes a silence cuts: the capture goes on)
        self._items(self.dissector.push(self.framer.finish(silence=True)))
        self._run()

    def _expire(self, stamp: Stamp, safe: Stamp | None = None) -> None:
        """The display's Dissector.expire(safe): safe is `stamp`, or the time of the first byte the
        Python framer holds if earlier (CaptureThread.safe_time)."""
        if self.timeout is None or self.done:
            return
        path = self.path
        if not path.python:
            held = self._held_time()
            if held is None or stamp - held <= self.timeout:
                return  # the request it may hold is not older than that: none expires
            if not self._to_python():
                return
        if safe is None:
            held = self.framer.held_since
            safe = stamp if held is None else min(stamp, held)
        self._items(self.dissector.expire(safe))
        self._run()

    # -- the stream between the engine and the Python stages ----------------------------------------------
    def _held_time(self) -> Stamp | None:
        """The time of the first byte the engine holds (None: it holds none)."""
        path = self.path
        offset = path.base + path.pos
        if offset >= path.base + len(path.buf) or not path.starts:
            return None
        return Stamp(path.times[path._chunk_of(offset)])

    def _to_python(self) -> bool:
        """The Python stages have the stream, framed as far as they can; False: the engine has it and
        holds no byte (the Python framer would hold none)."""
        path = self.path
        for _attempt in range(4):
            if path.python:
                return True
            if self._held_time() is None:
                return False
            path._hand_over()
            self._run()
        return path.python

    def _run(self) -> None:
        """Either side frames what it can with the chunks so far (TimedPath.feed's loop)."""
        path = self.path
        while path._python_frames() if path.python else path._engine_frames():
            pass


class _ReadBlocks(BlockBuilder):
    """BlockBuilder with a read added at once: its runs of bytes with one time (ReadClock.runs) are
    the block's chunks, their offsets, times and flags as add() gives each of them fed as a Chunk,
    the Chunks made only where the Python stages take the stream (Block.chunk)."""

    _step = -1.0  # the character time (us) _pausing was found for (timing.may_pause): the same for every read
    _pausing = True

    def add_read(self, data: bytes, times: ByteTimes, clock: ReadClock) -> list[Block] | None:
        """The blocks filled (None: none, the usual case: a generator costs as much as the rest)."""
        if times.step_us != self._step:
            self._step, self._pausing = times.step_us, may_pause(times.step_us, self.timing)
        offset = self.offset
        packed = None
        if not (self._pausing or not self.exact or self.size + len(data) >= self.block_bytes):
            packed = clock.packed(times, offset)
        if packed is not None:
            starts, ns = packed
            first, last = ns[0], ns[-1]
        if packed is None or first < -(1 << 62) or last >= 1 << 62:
            # (a silence inside the read, times the engine cannot subtract, a block full inside it:
            # rare, and exact as each run fed as a Chunk)
            runs, stamps = clock.runs(times)
            ends = [*runs[1:], len(data)]
            return [block for start, end, time in zip(runs, ends, stamps)
                    for block in self.add(Chunk(data[start:end], time=Stamp(time)))]
        count = len(starts)
        flags = bytearray((TIMED,)) * count
        if self.previous is not None and silence_before(self.previous, offset, Stamp(first), self.timing):
            flags[0] |= SILENCE_BEFORE
        self.previous = (starts[-1], Stamp(last))
        self.pieces.append(data)
        self.kept.extend([None] * count)
        self.starts += starts
        self.times += ns
        self.flags += flags
        self.offset += len(data)
        self.size += len(data)
        return None


class _CountedFramer:
    """The Python stages' framer with -c's cut (LivePath._cut_framed) on what it gives out; anything
    else is the framer's own. A copy (the trial of a flush) is the framer's, uncut."""

    def __init__(self, framer: Any, live: LivePath) -> None:
        object.__setattr__(self, "_framer", framer)
        object.__setattr__(self, "_live", live)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._framer, name)

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(self._framer, name, value)

    def __deepcopy__(self, memo: dict[int, Any]) -> Any:
        return copy.deepcopy(self._framer, memo)

    def feed(self, chunk: Chunk) -> list[Item]:
        return self._live._cut_framed(self._framer.feed(chunk))

    def finish(self, silence: bool = False) -> list[Item]:
        return self._live._cut_framed(self._framer.finish(silence))

    def finish_at(self, end: float | None) -> list[Item]:
        return self._live._cut_framed(self._framer.finish_at(end))
