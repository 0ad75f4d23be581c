"""When each byte of a serial port's reads came (app/live_capture.py frames them at these times).

A read returns once its last byte has come: its stamp is that byte's arrival, and byte k of an n-byte
read came about n-1-k character times earlier (a USB adapter delivers a request and its answer in one
read). So each byte's time is the stamp less the character times after it, never earlier than the
previous read's stamp (its bytes came first), nor than ADAPTER_HOLD before a read that gave none (an
adapter may hold bytes that long: a read that times out proves the line silent only until then),
unless the clock stepped back since (a stamp before those: the times start again from this read).
Times stay whole microseconds, as the pcap stores them.
"""
from __future__ import annotations

import sys
from array import array
from bisect import bisect_left, bisect_right
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

from dissector.model import Chunk, Stamp

# How long a USB adapter may keep bytes it has received before the port's read gives them: FTDI's
# latency timer, 16 ms by default, a USB frame and a margin. A read that times out says no byte came
# before its stamp less this (ReadClock.promise), so a request is shown unanswered that much later.
ADAPTER_HOLD_NS = 20_000_000
LITTLE = sys.byteorder == "little"  # packed() writes the int64s of a little-endian machine's arrays


@dataclass(slots=True)
class ByteTimes:
    """When each byte of a read came, each its own time: byte k of last + 1 at end_ns less
    round((last - k) * step_us) microseconds, never before floor_ns (ReadClock). A framer fed a read
    as one ByteTimedChunk times and weighs its bytes exactly as if each run of bytes with one time
    were a chunk of its own (framing/stream.py)."""

    end_ns: int
    last: int
    step_us: float
    floor_ns: int | None = None

    def ns(self, index: int) -> int:
        ns = self.end_ns - round((self.last - index) * self.step_us) * 1000
        floor = self.floor_ns
        return floor if floor is not None and ns < floor else ns

    def at(self, index: int) -> Stamp:
        return Stamp(self.ns(index))

    def last_run(self) -> int:
        """The first byte with the last byte's time (the start of the last run)."""
        index, ns = self.last, self.ns(self.last)
        while index and self.ns(index - 1) == ns:
            index -= 1
        return index

    def runs(self) -> Iterator[tuple[int, int]]:
        """(first byte, ns) of each run of bytes with one time, in order."""
        previous = None
        for index in range(self.last + 1):
            ns = self.ns(index)
            if ns != previous:
                yield index, ns
                previous = ns


@dataclass(slots=True)
class ByteTimedChunk(Chunk):
    """A read whose bytes each have a time (`times`); its `time` is its first byte's, times.at(0)."""

    times: ByteTimes | None = None



def char_time(baud: int, bytesize: int = 8, parity: str = "E", stopbits: float = 1) -> float:
    """Seconds a character takes on the wire: start bit, data bits, parity bit unless none, stop bits."""
    return (1 + bytesize + (parity != "N") + stopbits) / baud


class ReadClock:
    """The arrival time of each byte of the reads of a port, in order (the module's docstring).

    chunk() gives a read as one chunk that times each of its bytes (ByteTimedChunk):
    the framers frame it at once and time it as they would its runs of bytes with one time fed one by
    one (chunks(): the same times, a chunk for each run, which cost 5 times as much to frame); runs()
    gives those runs' offsets and times for the engine's arrays (accel/livepath.py)."""

    def __init__(self, char_time: float) -> None:
        self.char_us = char_time * 1e6
        self.floor: int | None = None  # ns: no byte still to come arrived before this
        # ns before the stamp of the byte j characters before the last (round(j * char_us) us): the
        # same products as ByteTimes.ns, made once for every read
        self._back: list[int] = [0]
        self._lanes = 0  # packed(): reads up to this many bytes, and their lanes
        self._ones = self._ramp = self._back_lanes = 0

    def byte_times(self, data: bytes, stamp: Stamp) -> ByteTimes | None:
        """The times of the bytes of a read stamped `stamp`; a read that timed out (no bytes) gives
        None and moves the floor (`promise`)."""
        floor = self.floor
        if floor is not None and stamp.ns < floor:
            # The wall clock stepped back (NTP): the earlier reads' times say nothing of this one's bytes,
            # which would otherwise all be held at the floor until the clock caught up with it.
            floor = None
        if not data:
            self.floor = self.promise(stamp).ns if floor is None else max(floor, self.promise(stamp).ns)
            return None
        self.floor = stamp.ns if floor is None else max(floor, stamp.ns)
        return ByteTimes(stamp.ns, len(data) - 1, self.char_us, floor)

    def chunk(self, data: bytes, stamp: Stamp) -> ByteTimedChunk | None:
        """A read as one chunk timing each byte (None: the read timed out, as byte_times)."""
        times = self.byte_times(data, stamp)
        return None if times is None else ByteTimedChunk(data, times.at(0), times=times)

    def chunks(self, data: bytes, stamp: Stamp) -> list[Chunk]:
        """The same read as a chunk for each run of bytes with one time (bytes held back to the floor
        share one); none for a read that timed out."""
        times = self.byte_times(data, stamp)
        if times is None:
            return []
        starts, ns = self.runs(times)
        ends = [*starts[1:], len(data)]
        return [Chunk(data[start:end], time=Stamp(time)) for start, end, time in zip(starts, ends, ns)]

    def runs(self, times: ByteTimes) -> tuple[Sequence[int], list[int]]:
        """(first byte, ns) of each run of a read's bytes with one time (ByteTimes.runs), at C speed
        where each byte has its own time: the line's characters more than 2 us long, as at any baud
        rate below 5 Mbit/s (then round(j * char_us) grows with j, and only the bytes held at the floor
        share a time)."""
        if self.char_us <= 2:
            found = list(times.runs())
            return [index for index, _ns in found], [ns for _index, ns in found]
        count = times.last + 1
        back = self._back
        if len(back) < count:
            char_us = self.char_us
            back.extend(round(j * char_us) * 1000 for j in range(len(back), count))
        ns = list(map(times.end_ns.__sub__, back[count - 1 :: -1]))
        floor = times.floor_ns
        if floor is None or ns[0] > floor:
            return range(count), ns
        held = bisect_right(ns, floor)  # the bytes before the floor, timed at it: one run
        return [0, *range(held, count)], [floor, *ns[held:]]

    def packed(self, times: ByteTimes, offset: int) -> tuple[array, array] | None:
        """runs() as the engine's arrays (int64 stream offsets from `offset`, ns), made without an int a
        byte: each array is one big integer of 64-bit lanes, the stamp (or offset) times a lane of ones
        less (plus) a lane of the back times (the ramp 0, 1, 2...), as bytes. None where that does not
        hold (characters of 2 us or less: runs(); times outside 0..2**62: no lane may borrow)."""
        count = times.last + 1
        if self.char_us <= 2 or times.end_ns >= 1 << 62 or not LITTLE:
            return None
        if self._lanes < count:
            self._grow(count)
        floor = times.floor_ns
        back = self._back
        # the bytes back-dated to the floor or before it (back[j] >= stamp - floor, j from the last)
        held = 0 if floor is None else count - bisect_left(back, times.end_ns - floor, 0, count)
        lanes = count - held
        if times.end_ns - back[lanes - 1 if lanes else 0] < 0:
            return None
        mask = (1 << 64 * lanes) - 1
        ones = self._ones & mask
        # lane j: the byte j before the last; big-endian bytes put the lanes in the bytes' order
        ns = array("q", (times.end_ns * ones - (self._back_lanes & mask)).to_bytes(8 * lanes, "big"))
        ns.byteswap()
        starts = array("q", ((offset + held) * ones + (self._ramp & mask)).to_bytes(8 * lanes, "little"))
        if held:
            return array("q", (offset,)) + starts, array("q", (floor,)) + ns  # type: ignore[arg-type]
        return starts, ns

    def _grow(self, count: int) -> None:
        """The lanes of packed() for reads up to `count` bytes (at least doubled: few regrowths)."""
        lanes = max(count, 2 * self._lanes, 64)
        back = self._back
        char_us = self.char_us
        back.extend(round(j * char_us) * 1000 for j in range(len(back), lanes))
        self._lanes = lanes
        # (from the bytes of an array: a sum of shifted ints would take time quadratic in the lanes)
        self._ones = int.from_bytes((array("q", (1,)) * lanes).tobytes(), "little")
        self._ramp = int.from_bytes(array("q", range(lanes)).tobytes(), "little")
        self._back_lanes = int.from_bytes(array("q", back[:lanes]).tobytes(), "little")

    @staticmethod
    def promise(stamp: Stamp) -> Stamp:
        """No byte still to come is timed before this, after a read stamped `stamp` that timed out:
        the adapter may hold bytes that had come (ADAPTER_HOLD), which the next read gives."""
        return Stamp(stamp.ns - ADAPTER_HOLD_NS)
