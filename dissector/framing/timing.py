"""Timing anomalies seen in timestamped captures: a silence inside a frame.

On the wire, the characters of an RTU frame follow each other with less than 1.5 character times
of silence (t1.5); a longer pause makes a conforming receiver drop the frame. In ASCII mode the
limit is one second between characters. Timestamps come with the chunks a source delivers (pcap
records, hex-dump lines, live reads), each the time of the chunk's first byte (model.Chunk), so the
silence before a chunk that starts inside a frame is

    time of that chunk - time of the previous chunk - transmission time of the previous chunk's bytes

and a frame that spans chunks separated by more than the limit is reported. The framer never uses
this to cut frames (length rules and CRC decide); it is a finding for the user. Response timeouts
are the pairer's business, not this module's.

Serial Line Guide v1.02, 2.5.1.1: an RTU character is 11 bits (start, 8 data, parity or a second
stop bit, stop); t1.5 is 1.5 character times up to 19200 baud and a fixed 750 us above, where the
character time would be too short for UARTs' interrupt handling. An ASCII character is 10 bits
(start, 7 data, parity, stop), with intervals of up to 1 s allowed between characters.
"""
from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from dissector.model import Chunk, Frame, Item, Stamp
from dissector.protocol.rules import text

if TYPE_CHECKING:
    from dissector.sources.serial_times import ByteTimes

DEFAULT_BAUD = 19200
RTU_BITS_PER_CHAR = 11
ASCII_BITS_PER_CHAR = 10
FIXED_TIMING_ABOVE = 19200  # baud rate above which t1.5 and t3.5 are fixed
FIXED_T15 = 750e-6
FIXED_T35 = 1750e-6
ASCII_MAX_SILENCE = 1.0
# How a silence inside a frame names the limit it passed (describe_limit; the plugin's DATA.timing).
RTU_LIMIT = "t1.5 = {t15_ms:.3f} ms at {baud:d} baud"
ASCII_LIMIT = "the 1 s ASCII limit"


def mode_bits(mode: str) -> int:
    """The bits of a character in `mode` (above): 11 RTU, 10 ASCII."""
    return ASCII_BITS_PER_CHAR if mode == "ascii" else RTU_BITS_PER_CHAR


@dataclass(frozen=True, slots=True)
class LineTiming:
    baud: int = DEFAULT_BAUD
    mode: str = "rtu"

    @property
    def char_time(self) -> float:
        return mode_bits(self.mode) / self.baud

    @property
    def t15(self) -> float:
        return self._rtu_interval(1.5, FIXED_T15)

    @property
    def t35(self) -> float:
        return self._rtu_interval(3.5, FIXED_T35)

    def _rtu_interval(self, characters: float, fixed: float) -> float:
        """`characters` RTU character times, or `fixed` s above FIXED_TIMING_ABOVE baud (2.5.1.1, above)."""
        return fixed if self.baud > FIXED_TIMING_ABOVE else characters * RTU_BITS_PER_CHAR / self.baud

    @property
    def max_silence(self) -> float:
        """The longest silence allowed between two characters of one frame."""
        return ASCII_MAX_SILENCE if self.mode == "ascii" else self.t15

    def describe_limit(self) -> str:
        if self.mode == "ascii":
            return ASCII_LIMIT
        return RTU_LIMIT.format(t15_ms=self.t15 * 1000, baud=self.baud)


def line_silence(previous_offset: int, previous_time: float, start: int, time: float, timing: LineTiming) -> float:
    """Seconds the line was silent before the chunk at stream offset `start` that came at `time`, after
    the chunk at `previous_offset` that came at `previous_time`: the formula above, for a silence inside
    a frame (inner_gaps) and between frames (silence_before) alike; _timeline.h line_silence in C."""
    return time - previous_time - (start - previous_offset) * timing.char_time


def inner_gaps(
    offset: int,
    length: int,
    starts: Sequence[tuple[int, float | None]],
    timing: LineTiming,
) -> list[str]:
    """Warnings for silences longer than allowed inside the frame at [offset, offset + length).

    `starts` holds (absolute stream offset, time) of consecutive chunk starts in stream order,
    including at least the chunk the frame starts in (as the framers keep them).
    """
    warnings: list[str] = []
    end = offset + length
    for (previous_offset, previous_time), (start, time) in zip(starts, starts[1:]):
        if not offset < start < end or previous_time is None or time is None:
            continue
        silence = line_silence(previous_offset, previous_time, start, time, timing)
        if silence > timing.max_silence:
            warnings.append(text(
                "inner_silence", silence_ms=silence * 1000, byte=start - offset, limit=timing.describe_limit()
            ))
    return warnings


class GapChecker:
    """Sees the chunks a framer is fed and checks the items that framer returns.

    Usage: `checker.observe(chunk)` for every chunk before feeding it to the framer, then
    `item.warnings += checker.check(item)` for every item the framer returns, in order (noise
    too: checking an item lets the checker forget the chunks before it, so memory stays bounded).
    """

    def __init__(self, baud: int = DEFAULT_BAUD, mode: str = "rtu") -> None:
        self.timing = LineTiming(baud, mode)
        self._starts: list[tuple[int, float | None]] = []
        self._position = 0

    def observe(self, chunk: Chunk) -> None:
        if chunk.data:
            self._starts.append((self._position, chunk.time))
            self._position += len(chunk.data)

    def take_over(self, chunk_start: int, chunk: Chunk) -> None:
        """Observe from inside `chunk` (stream offset chunk_start) on: the chunks before it were framed
        elsewhere (dissector/accel/timedpath.py)."""
        self._starts = [(chunk_start, chunk.time)]
        self._position = chunk_start + len(chunk.data)

    def check(self, item: Item) -> list[str]:
        end = item.offset + item.length
        warnings: list[str] = []
        if isinstance(item, Frame):
            warnings = inner_gaps(item.offset, item.length, self._starts, self.timing)
        # Keep the last chunk starting at or before the end: it precedes any later frame's bytes.
        starts = self._starts
        keep = 0
        for index, (start, _time) in enumerate(starts):
            if start <= end:
                keep = index
            else:
                break
        if keep:
            del starts[:keep]
        return warnings


def silence_before(previous: tuple[int, float | None], start: int, time: float, timing: LineTiming) -> bool:
    """Was the line silent for t3.5 or more before the chunk that starts at stream offset `start` and
    came at `time`, after the chunk (offset, time) `previous`? The framers take it as evidence that a
    frame may end there (a record boundary's weight), never as a cut: a USB adapter's reads come in
    bursts whose times say little about the gaps inside them."""
    offset, before = previous
    return before is not None and line_silence(offset, before, start, time, timing) >= timing.t35



def may_pause(step_us: float, timing: LineTiming) -> bool:
    """Could the line look silent for t3.5 inside a read whose bytes came `step_us` apart (a serial
    port's: sources/serial_times.py ByteTimes), between two of its runs of bytes with one time? Their
    times differ by at most step_us + 1 us (each rounded to the us) and the bytes of the first take a
    character or more, so not unless the step is far longer than the line's characters."""
    return (step_us + 1) * 1e-6 - timing.char_time >= timing.t35 / 2


def silences_inside(times: ByteTimes, start: int, timing: LineTiming) -> Iterator[int]:
    """Stream offsets (of the read starting at `start`) of the runs of its bytes after which
    silence_before holds from the run before: what feeding each run as a chunk would mark."""
    if not may_pause(times.step_us, timing):
        return
    previous: tuple[int, float | None] | None = None
    for index, ns in times.runs():
        time = Stamp(ns)
        if previous is not None and silence_before(previous, start + index, time, timing):
            yield start + index
        previous = (start + index, time)
