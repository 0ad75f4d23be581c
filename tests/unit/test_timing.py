"""Silences inside frames, from chunk timestamps (dissector.framing.timing)."""
from __future__ import annotations

import pytest

from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame
from dissector.framing.timing import GapChecker, LineTiming, inner_gaps
from helpers import hx

REQUEST = hx("0C 03 20 D0 00 03 0E EF")
RESPONSE = hx("0C 03 06 80 00 00 03 00 02 17 E4")
CHAR_19200 = 11 / 19200


@pytest.mark.parametrize(
    ("baud", "char_time", "t15", "t35"),
    [
        (9600, 11 / 9600, 1.5 * 11 / 9600, 3.5 * 11 / 9600),
        (19200, 11 / 19200, 1.5 * 11 / 19200, 3.5 * 11 / 19200),
        (38400, 11 / 38400, 750e-6, 1750e-6),
        (115200, 11 / 115200, 750e-6, 1750e-6),
    ],
)
def test_line_timing(baud: int, char_time: float, t15: float, t35: float) -> None:
    timing = LineTiming(baud)
    assert (timing.char_time, timing.t15, timing.t35, timing.max_silence) == (char_time, t15, t35, t15)


def test_ascii_allows_one_second() -> None:
    timing = LineTiming(9600, "ascii")
    assert (timing.char_time, timing.max_silence) == (10 / 9600, 1.0)


def test_inner_gap_subtracts_the_transmission_of_earlier_bytes() -> None:
    timing = LineTiming()
    sent = 4 * CHAR_19200  # the first four bytes take this long on the wire
    # 0.8 ms of silence: under t1.5 (0.859 ms) at 19200 baud.
    assert inner_gaps(0, 8, [(0, 10.0), (4, 10.0 + sent + 0.0008)], timing) == []
    assert inner_gaps(0, 8, [(0, 10.0), (4, 10.0 + sent + 0.002)], timing) == [
        "silence of 2.000 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)"]
    # A chunk starting exactly at the frame's start or end is not inside the frame.
    assert inner_gaps(4, 4, [(0, 10.0), (4, 20.0), (8, 30.0)], timing) == []
    # Unknown times say nothing.
    assert inner_gaps(0, 8, [(0, None), (4, 20.0)], timing) == []


def _checked(framer: RtuFramer | AsciiFramer, checker: GapChecker, chunks: list[Chunk]) -> list:
    items = []
    for chunk in chunks:
        checker.observe(chunk)
        items += framer.feed(chunk)
    items += framer.finish()
    for item in items:
        item.warnings += checker.check(item)
    return items


def test_gap_checker_flags_the_split_frame_only() -> None:
    checker = GapChecker(baud=19200)
    chunks = [
        Chunk(REQUEST, 1.0),
        # The response arrives in two reads 5 ms apart: 3 bytes take 1.72 ms, so 3.28 ms of silence.
        Chunk(RESPONSE[:3], 1.020),
        Chunk(RESPONSE[3:], 1.025),
        Chunk(REQUEST, 2.0),
    ]
    items = _checked(RtuFramer(), checker, chunks)
    assert [type(i) for i in items] == [Frame, Frame, Frame]
    silence = 0.005 - 3 * CHAR_19200
    assert [i.warnings for i in items] == [
        [], [f"silence of {silence * 1000:.3f} ms inside the frame before byte 3 "
             "(longer than t1.5 = 0.859 ms at 19200 baud)"], []]
    # Checking an item forgets the chunks before it: memory stays bounded.
    assert len(checker._starts) == 1


def test_gap_checker_back_to_back_chunks_are_not_flagged() -> None:
    # The same response in 1-byte reads, each at the time its byte ends up on the wire.
    chunks = [Chunk(REQUEST, 0.0)] + [
        Chunk(RESPONSE[k : k + 1], 0.010 + k * CHAR_19200) for k in range(len(RESPONSE))]
    items = _checked(RtuFramer(), GapChecker(), chunks)
    assert [i.warnings for i in items] == [[], []]


def test_gap_checker_ascii_mode() -> None:
    frame = b":02062329000AA2\r\n"
    chunks = [Chunk(frame[:5], 0.0), Chunk(frame[5:], 1.5), Chunk(frame, 3.0), Chunk(frame[:3], 4.0),
              Chunk(frame[3:], 4.5)]
    items = _checked(AsciiFramer(), GapChecker(baud=9600, mode="ascii"), chunks)
    silence = 1.5 - 5 * 10 / 9600
    assert [i.warnings for i in items] == [
        [f"silence of {silence * 1000:.3f} ms inside the frame before byte 5 "
         "(longer than the 1 s ASCII limit)"],
        [], []]
