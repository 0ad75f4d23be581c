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

from dissector.model import Chunk, Stamp

# How long a USB adapter may keep bytes it has received before the port's read gives them: FTDI's
# latency timer, 16 ms by default, a USB frame and a margin. A read that times out says no byte came
# before its stamp less this (ReadClock.promise), so a request is shown unanswered that much later.
ADAPTER_HOLD_NS = 20_000_000


def char_time(baud: int, bytesize: int = 8, parity: str = "E", stopbits: float = 1) -> float:
    """Seconds a character takes on the wire: start bit, data bits, parity bit unless none, stop bits."""
    return (1 + bytesize + (parity != "N") + stopbits) / baud


class ReadClock:
    """The arrival time of each byte of the reads of a port, in order (the module's docstring)."""

    def __init__(self, char_time: float) -> None:
        self.char_us = char_time * 1e6
        self.floor: int | None = None  # ns: no byte still to come arrived before this

    def chunks(self, data: bytes, stamp: Stamp) -> list[Chunk]:
        """The bytes of a read stamped `stamp`, a chunk for each arrival time (bytes held back to the
        floor share one); a read that timed out (no bytes) gives none and moves the floor (`promise`)."""
        floor = self.floor
        if floor is not None and stamp.ns < floor:
            # The wall clock stepped back (NTP): the earlier reads' times say nothing of this one's bytes,
            # which would otherwise all be held at the floor until the clock caught up with it.
            floor = None
        if not data:
            self.floor = self.promise(stamp).ns if floor is None else max(floor, self.promise(stamp).ns)
            return []
        self.floor = stamp.ns if floor is None else max(floor, stamp.ns)
        last = len(data) - 1
        chunks: list[Chunk] = []
        start = 0
        previous: int | None = None
        char_us = self.char_us
        for index in range(last + 1):
            ns = stamp.ns - round((last - index) * char_us) * 1000
            if floor is not None and ns < floor:
                ns = floor
            if ns != previous:
                if previous is not None:
                    chunks.append(Chunk(data[start:index], time=Stamp(previous)))
                start, previous = index, ns
        chunks.append(Chunk(data[start:], time=Stamp(previous)))  # type: ignore[arg-type]
        return chunks

    @staticmethod
    def promise(stamp: Stamp) -> Stamp:
        """No byte still to come is timed before this, after a read stamped `stamp` that timed out:
        the adapter may hold bytes that had come (ADAPTER_HOLD), which the next read gives."""
        return Stamp(stamp.ns - ADAPTER_HOLD_NS)
