"""What both framers (RTU and ASCII) keep between chunks: the bytes not framed yet, the time each
chunk arrived, the expectation of an answer, and the noise run being built.

A chunk may time each of its bytes (sources/serial_times.py ByteTimedChunk: a serial port's read, its
bytes a character apart): it is framed, timed and weighed as the chunks of its runs of bytes with one
time would be, fed one by one (live capture fed those from 4173324 to 09ae941, and framed each byte on
its own: 5 times the work, bench/live_feed.py)."""
from __future__ import annotations

from abc import ABC, abstractmethod
from bisect import bisect_right
from operator import itemgetter

from dissector.framing.answers import answer_length
from dissector.framing.offsets import EndAnswers, Offsets
from dissector.framing.timing import DEFAULT_BAUD, LineTiming, may_pause, silence_before, silences_inside
from dissector.model import CapturedPart, Chunk, Frame, Item, Kind, Noise, Tail
from dissector.protocol.rules import awaits_answer, echoed
from dissector.sources.common import PartChunk
from dissector.sources.serial_times import ByteTimedChunk, ByteTimes

NOISE_ITEM_MAX = 4096  # noise runs are cut into items of this size: memory stays bounded on garbage
# What a short low pulse on an idle line reads as: a start bit, k zero bits, then ones (FF << k). A bus
# driver's turn-around leaves one after a frame (the sigrok-dumps wizmodbus line: 00 after requests,
# FE after responses); a break reads as 00, an idle line's noise as FF.
GLITCH_BYTES = frozenset((0xFF << k) & 0xFF for k in range(9))
_GLITCHES = bytes(sorted(GLITCH_BYTES))
GLITCH_RUN = 16  # the longest run of glitch bytes between two frames that says the line leaves glitches
GLITCHY_AFTER = 3
GLITCH_SCORE_MAX = 8
# The reason of the item a record captured in part is (StreamFramer._cut_part); lua/src/stream.lua says the same.
CAPTURED_IN_PART = "captured in part"
_chunk_start = itemgetter(0)  # (StreamFramer._times' entries by their stream offset)


def part_reason(part: CapturedPart) -> str:
    """`captured in part (5 of its 9 bytes; slave 2, function 3; the answer to #1): its CRC cannot be checked`."""
    told = ([] if part.slave is None else [f"slave {part.slave}"]) + (
        [] if part.function is None else [f"function {part.function}"])
    fields = "; " + ", ".join(told) if told else ""
    answer = "" if part.answers is None else f"; the answer to #{part.answers}"
    return (f"{CAPTURED_IN_PART} ({part.captured} of its {part.original} bytes{fields}{answer}): "
            f"its {part.check} cannot be checked")


class StreamFramer(ABC):
    """Push parser: feed chunks, collect items in stream order, unnumbered.

    finish() closes whatever is buffered (a frame or noise) and leaves the framer ready for more
    bytes with its expectation kept: live capture calls it after a silence on the line.
    """

    mode: str

    def __init__(self, baud: int = DEFAULT_BAUD) -> None:
        self._timing = LineTiming(baud, self.mode)  # what a silence between chunks is (silence_before)
        self._buf = bytearray()
        self._base = 0  # absolute offset of _buf[0]
        # (absolute offset, time, its bytes' times or None) of chunk starts
        self._times: list[tuple[int, float | None, ByteTimes | None]] = []
        self._timed = False
        self._steady_step = -1.0  # a ByteTimes.step_us with which no silence is inside a chunk (timing.may_pause)
        # Where a source said a frame boundary is (a pcap record's end): breaks ties between layouts.
        self._boundaries = Offsets()
        # Where a chunk that ends a record (boundary=True: a pcap record, fed whole) starts, kept apart from
        # the boundaries (a silence is one too): a record that is one frame is the source's word (rtu.py).
        self._record_starts = Offsets()
        # Where a silence of t3.5 or more is (kept apart from the record ends): noise bytes after one cannot be
        # the same frame's as the ones before, so a noise run is given out as one item per stretch between them.
        self._silences = Offsets()
        # A record end's answer to reach.py _ends_record, with the state it was given in (the stream's end, the
        # answer awaited, its echo) and the stream's end up to which it holds: each CRC scan weighs the record ends
        # ahead of it, asked again for every start (reach.py _framed_reach).
        self._ends_memo = EndAnswers()
        self._noise = bytearray()
        self._noise_offset = 0
        self._noise_reason = ""
        self._noise_time: float | None = None
        # (index in _noise, reason, time, the Tail of the stretch before) of each stretch after a silence inside the
        # run (_add_noise): the run stays one for the framer's decisions (fast path, repeats, glitches), its items
        # are cut there.
        self._noise_parts: list[tuple[int, str, float | None, Tail | None]] = []
        self._noise_tail: Tail | None = None  # of the run's last byte (its bytes' times are gone once consumed)
        # Every noise byte since the last frame (or boundary) is a glitch byte (rtu.GLITCH_BYTES): the
        # next frame start is still where one is expected (RtuFramer._anchored).
        self._glitches_only = True
        self._noise_cut = False  # the noise run goes on past an item cut at NOISE_ITEM_MAX bytes
        # How much the line shows 00 glitches: +1 for a frame after nothing but a few glitch bytes, a 00
        # among them, after a frame; -1 for one after other noise (a damaged line's); at most
        # GLITCH_SCORE_MAX. From GLITCHY_AFTER on, a 00 after a frame is a glitch, not the last byte of
        # a frame one byte longer (both check: CRC-16/MODBUS has no final XOR).
        self._glitch_runs = 0
        self._expect: tuple[int, int] | None = None  # (slave, function) awaiting a response
        # What its normal answer repeats of the request ([pairing] echo, an FC8 sub-function; b"": nothing or not
        # known, after a hand-over): a frame of that slave and function that does not is the master's next request.
        self._echo = b""
        # The length of the normal answer awaited, where its request fixes it (answers.py; None: not known, after a
        # hand-over too): a response reading of another length the end of the capture cuts is not that answer.
        self._answer: int | None = None
        # Frame nothing that starts at or after this absolute offset yet (see pause_at).
        self._pause: int | None = None
        self._framed_end = -1  # absolute offset where the last frame ends (-1: none yet): a bound (bounded.py)
        self._cut_by_silence = False  # finish(silence=True) runs: what it cuts, a silence cuts
        self._ready: list[Item] = []  # items made where no call gives them out (take_over's cut), for the next
        # Records captured in part cut (_cut_part) and their bytes: a capture of nothing else is said so (app/cli.py).
        self.cut_records = self.cut_bytes = 0

    def feed(self, chunk: Chunk) -> list[Item]:
        if type(chunk) is PartChunk:  # (none of its bytes captured too: bytes were lost there all the same)
            return self._cut_part(chunk)
        if chunk.data:
            start = self._base + len(self._buf)
            byte_times = chunk.times if isinstance(chunk, ByteTimedChunk) else None
            if chunk.time is not None:
                self._timed = True
                if self._silent_until(chunk.time):
                    self._boundaries.add(start)  # a silence on the line: evidence, like a record's end
                    self._silences.add(start)
                if byte_times is not None and byte_times.step_us != self._steady_step:
                    if may_pause(byte_times.step_us, self._timing):
                        # (a list: both sets take it, an iterator would fill the first alone)
                        inside = list(silences_inside(byte_times, start, self._timing))
                        self._boundaries.update(inside)
                        self._silences.update(inside)
                    else:
                        self._steady_step = byte_times.step_us  # (every read of a port has the same)
            self._times.append((start, chunk.time, byte_times))
            self._buf += chunk.data
            if chunk.boundary:
                self._boundaries.add(self._base + len(self._buf))
                self._record_starts.add(start)
        return self._given(self._run(final=False))

    def _given(self, items: list[Item]) -> list[Item]:
        """`items`, after those made before them that no call could give out (take_over's)."""
        if self._ready:
            items[:0] = self._ready
            self._ready = []
        return items

    def _cut_part(self, chunk: PartChunk) -> list[Item]:
        """A record captured in part: the line's bytes after it were lost. What came before it is closed (no frame
        goes on into it), its bytes are one item that says so (no CRC or LRC can be checked on a frame cut
        short; what its bytes tell, _part_fields), and the next record's bytes frame from a clean start (none
        awaited, as after a hand-over). Without the cut, its bytes and the next record's made a frame with a
        bad CRC and noise (editcap -s 5 on a real capture)."""
        # (all of it, as the Python stages alone frame it: a caller taking frames one at a time, pause_at, gets
        # the items before the cut at once rather than bytes lost under it)
        pause, self._pause = self._pause, None
        try:
            items = self._given(self._run(final=True))
        finally:
            self._pause = pause
        self._flush_noise(items)
        start = self._base + len(self._buf)  # (the buffer is empty: finish consumes it)
        data = bytes(chunk.data)
        part = CapturedPart(chunk.captured, chunk.original, "LRC" if self.mode == "ascii" else "CRC",
                            *self._part_fields(data))
        if chunk.time is not None:
            self._timed = True
        items.append(Noise(offset=start, raw=data, time=chunk.time, reason=part_reason(part), part=part))
        self.cut_records += 1
        self.cut_bytes += len(data)
        end = start + len(data)
        self.restart_at(end, None)
        self._framed_end = -1  # (no frame ends there: the next record starts at a boundary)
        self._times = [(start, chunk.time, None)]
        self._boundaries.add(end)
        return items

    def _part_fields(self, data: bytes) -> tuple[int | None, int | None]:
        """What the bytes of a frame cut short tell: its slave and function, None where not captured (RTU;
        ascii.py reads its hex)."""
        return (data[0] if data else None), (data[1] if len(data) > 1 else None)

    def finish(self, silence: bool = False) -> list[Item]:
        """Close what is buffered; `silence`: live closes it at a silence on the line, and the capture goes on
        (a frame cut there is cut by the silence, not by the end of the capture: rules.Awaiting._cut_reason)."""
        self._cut_by_silence = silence
        try:
            items = self._given(self._run(final=True))
        finally:
            self._cut_by_silence = False
        self._flush_noise(items)
        return items

    def finish_at(self, end: float | None) -> list[Item]:
        """Close what is buffered at the end of the capture, the tap recording until `end` (a file's last record,
        live's stop; None: not known). The line silent from its last bytes until then, as a silence is before the
        next bytes (_silent_until), cut what the framer holds, as live closes it at a silence: the capture went on
        past it (a file said the capture's end cut the answer live said a silence cut: hunt66b); else the end
        did. In ASCII no silence cuts (silence_cuts)."""
        return self.finish(silence=end is not None and self.silence_cuts and self._silent_until(end))

    @property
    def silence_cuts(self) -> bool:
        """Does a silence on this line cut a frame or a noise run? RTU's, of t3.5 (_silent_until); an ASCII
        frame ends at its LF and may hold a second's silence (timing.ASCII_LIMIT): live closes nothing at one
        (live_capture.CaptureThread.flush_due) and a file cuts nothing there (_add_noise, finish_at)."""
        return self.mode == "rtu"

    def _silent_until(self, time: float) -> bool:
        """Was the line silent t3.5 or more (timing.silence_before) from the last bytes fed until `time`: before
        the next chunk (feed), before the end of the capture (finish_at)? The one rule of what a silence is."""
        return bool(self._times) and silence_before(self._last_run(), self._base + len(self._buf), time,
                                                    self._timing)

    @property
    def timing(self) -> LineTiming:
        """The line's timing: what a silence between chunks is."""
        return self._timing

    # -- handing the stream over to another framing engine (dissector/accel/fastsummary.py) ------------
    @property
    def offset(self) -> int:
        """Absolute offset of the first byte not framed yet."""
        return self._base

    @property
    def idle(self) -> bool:
        """No noise run is being built: what was framed so far has all been given out."""
        return not self._noise and not self._ready

    @property
    def held_since(self) -> float | None:
        """Time of the first byte not framed yet (None: none held): no frame to come is earlier."""
        return self._time_at(self._base) if self._buf else None

    def pause_at(self, offset: int | None) -> None:
        """Start no frame at or after `offset` (None: no pause): lets a caller take items one frame
        at a time, to find the points where the stream can change hands."""
        self._pause = offset

    def restart_at(self, offset: int, expect: tuple[int, int] | None) -> None:
        """Take the stream up from absolute `offset`, where another engine left it idle."""
        self._buf = bytearray()
        self._base = offset
        self._times = []
        self._boundaries = Offsets()
        self._record_starts = Offsets()
        self._silences = Offsets()
        self._ends_memo = EndAnswers()
        self._expect = expect
        self._echo = b""  # (the engine hands over where the frame there is no answer to check: not known)
        self._answer = None
        self._glitches_only = True
        self._noise_cut = False
        # (the engine leaves the stream idle right after a frame it took, unless it took none)
        self._framed_end = offset if offset else -1

    def take_over(self, offset: int, expect: tuple[int, int] | None, chunk_start: int, chunk: Chunk) -> None:
        """restart_at(offset) inside `chunk`, which starts at stream offset chunk_start: the bytes of it
        from offset on are buffered as its feed() left them (its time, the record's end), so that the
        chunks fed after it are timed and weighed as if the stream had never changed hands. A record captured in
        part is cut as feed() cuts it (its item given out with the next call's)."""
        if type(chunk) is PartChunk and offset < chunk_start + len(chunk.data):
            self.restart_at(offset, expect)
            part = chunk.data[offset - chunk_start :]
            self._ready += self._cut_part(PartChunk(part, chunk.time, True, chunk.record, chunk.comments,
                                                    chunk.captured, chunk.original))
            return
        self.restart_at(offset, expect)
        self._timed = self._timed or chunk.time is not None
        byte_times = chunk.times if isinstance(chunk, ByteTimedChunk) else None
        self._times = [(chunk_start, chunk.time, byte_times)]
        self._buf += chunk.data[offset - chunk_start :]
        if byte_times is not None and chunk.time is not None:
            inside = [at for at in silences_inside(byte_times, chunk_start, self._timing) if at >= offset]
            self._boundaries.update(inside)
            self._silences.update(inside)
        if chunk.boundary:
            self._boundaries.add(chunk_start + len(chunk.data))
            self._record_starts.add(chunk_start)

    def hand_back(self) -> tuple[int, bytes, tuple[int, int] | None]:
        """(offset, bytes not framed yet, expectation) for another engine; the buffer is emptied."""
        rest = bytes(self._buf)
        self._base += len(self._buf)
        self._buf = bytearray()
        self._times = []
        return self._base - len(rest), rest, self._expect

    @abstractmethod
    def _run(self, final: bool) -> list[Item]:
        """Frame what the buffer holds; with final, nothing more will come."""

    def _time_at(self, offset: int) -> float | None:
        if not self._timed:
            return None
        times = self._times
        # Chunks are few per frame: walk back from the newest.
        for index in range(len(times) - 1, -1, -1):
            start, time, byte_times = times[index]
            if start <= offset:
                return time if byte_times is None or time is None else byte_times.at(offset - start)
        return None

    def _tail_at(self, end: int, offset: int = -1) -> Tail | None:
        """An item's Tail (model.sent_in) that ends at absolute offset `end`: the time of the run of bytes with
        one time holding its last byte and the characters from that run's first byte to `end`; None where that
        run starts at `offset` (the item's first byte: its time and length say it) or has no time."""
        times = self._times
        if not self._timed or not times:
            return None
        index = bisect_right(times, end - 1, key=_chunk_start) - 1
        if index < 0:
            return None
        start, time, byte_times = times[index]
        if time is None:
            return None
        if byte_times is not None:
            last = end - 1 - start
            ns = byte_times.ns(last)
            while last and byte_times.ns(last - 1) == ns:  # (to the start of its run: bytes held at the floor)
                last -= 1
            start, time = start + last, byte_times.at(last)
        return None if start == offset else (time, end - start)

    def _last_run(self) -> tuple[int, float | None]:
        """(offset, time) of the last bytes fed with one time: the chunk before the next, for silence_before."""
        start, time, byte_times = self._times[-1]
        if byte_times is None or time is None:
            return start, time
        index = byte_times.last_run()
        return start + index, byte_times.at(index)

    def _consume(self, count: int) -> None:
        """Drop the first `count` buffered bytes (framed or noise) and the chunk times before them."""
        del self._buf[:count]
        self._base += count
        times = self._times
        keep = 0
        for index, (offset, _time, _byte_times) in enumerate(times):
            if offset <= self._base:
                keep = index
        if keep:
            del times[:keep]
        # (a boundary at the new base still counts: the next run starts there, however the feeding went)
        self._boundaries.drop_below(self._base)
        self._record_starts.drop_below(self._base)
        self._silences.drop_below(self._base)

    def _boundary_at(self, index: int) -> bool:
        """Did the source mark a frame boundary after buffer index `index`?"""
        return self._base + index in self._boundaries

    def _record_starts_at(self, index: int) -> bool:
        """Does a chunk that ends a record start at buffer index `index` (kept where another engine hands
        the stream over inside it, take_over, as the record's end before it is not)?"""
        return self._base + index in self._record_starts

    def _add_noise(self, start: int, end: int, reason: str, items: list[Item]) -> None:
        """Bytes start..end of the buffer belong to no frame."""
        buf = self._buf
        if not self._noise and not self._noise_cut:
            self._glitches_only = True  # a new run, right after a frame
        check_from = start
        if self._boundaries:
            # A boundary inside the run starts the glitch rule anew: only the bytes after it count.
            inside = self._boundaries.within(self._base + start, self._base + end)
            if inside:
                self._glitches_only = True
                check_from = inside[-1] - self._base
        if self._glitches_only:
            self._glitches_only = not buf[check_from:end].translate(None, _GLITCHES)
        if self._silences and self.silence_cuts:
            base = self._base
            for at in [offset - base for offset in self._silences.within(base + start, base + end)]:
                if at > start:
                    self._add_run(start, at, reason, items)
                # (a silence right where a run was cut at NOISE_ITEM_MAX starts the next item anyway)
                if self._noise:
                    self._noise_parts.append((len(self._noise), reason, self._time_at(base + at), self._noise_tail))
                start = at
        self._add_run(start, end, reason, items)

    def _add_run(self, start: int, end: int, reason: str, items: list[Item]) -> None:
        """Bytes start..end of the buffer go to the noise run (no silence inside them)."""
        buf = self._buf
        while start < end:
            if not self._noise:
                self._noise_offset = self._base + start
                self._noise_reason = reason
                self._noise_time = self._time_at(self._noise_offset)
            take = min(end - start, NOISE_ITEM_MAX - len(self._noise))
            self._noise += buf[start : start + take]
            start += take
            self._noise_tail = self._tail_at(self._base + start)
            if len(self._noise) >= NOISE_ITEM_MAX:
                self._flush_noise(items)
                self._noise_cut = True

    @property
    def glitchy(self) -> bool:
        """Has the line shown 00 glitch bytes between frames (GLITCHY_AFTER times)?"""
        return self._glitch_runs >= GLITCHY_AFTER

    def _emit(self, frame: Frame, items: list[Item]) -> None:
        """A frame is found: close the noise before it, and expect the answer to a request that awaits one
        (protocol/rules.py awaits_answer: not a broadcast, not FC8 04 Force Listen Only Mode)."""
        noise = self._noise
        if noise:
            if self._glitches_only and len(noise) <= GLITCH_RUN and self._noise_offset and not self._noise_cut:
                if 0 in noise:
                    self._glitch_runs = min(GLITCH_SCORE_MAX, self._glitch_runs + 1)
            elif self._glitch_runs:
                self._glitch_runs -= 1
        self._flush_noise(items)
        self._noise_cut = False
        frame.tail = self._tail_at(frame.offset + len(frame.raw), frame.offset)
        items.append(frame)
        self._await_after(frame)

    def _await_after(self, frame: Frame) -> None:
        """The answer a frame leaves awaited: a request's that awaits one, with what it must echo and its length;
        else none."""
        if frame.kind is Kind.REQUEST and awaits_answer(frame):
            self._expect = (frame.slave, frame.function)
            self._echo = echoed(frame)
            self._answer = answer_length(frame)
        else:
            self._expect = None
        self._framed_end = frame.offset + len(frame.raw)

    def _flush_noise(self, items: list[Item]) -> None:
        if self._noise:
            noise, parts = self._noise, self._noise_parts
            cuts = [(0, self._noise_reason, self._noise_time, None), *parts, (len(noise), "", None, self._noise_tail)]
            for (begin, reason, time, _tail), (stop, _reason, _time, tail) in zip(cuts, cuts[1:]):
                raw = bytes(noise[begin:stop])
                items.append(Noise(offset=self._noise_offset + begin, raw=raw, time=time, reason=reason, tail=tail))
            self._noise = bytearray()
            self._noise_parts = []
