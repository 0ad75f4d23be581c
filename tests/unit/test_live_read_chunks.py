"""A live read framed as one chunk that times each byte (ReadClock.chunk, ByteTimedChunk) gives
what the chunks of its runs of bytes with one time (ReadClock.chunks: what live capture fed from
4173324 on, 10 times the framing work) give fed one by one: the same items at the same reads, every
field, times to the nanosecond, and the same silences weighed; the engine's blocks (livepath._ReadBlocks)
the same arrays and chunks, the engine's live path the same lines.

The reads: simulated traffic cut as a USB adapter delivers it (1..n bytes a read, stamped when the
last came, empty reads in silences), with noise, a wall clock stepped back, bursts held at the floor
(bytes back-dated before the previous read), and port character times that are not the framer's
(8N1, 8N2) or far longer than its t3.5 (silences inside a read: timing.silences_inside)."""
from __future__ import annotations

import dataclasses
import random

import pytest

from dissector.accel.livepath import LivePath, _ReadBlocks
from dissector.accel.records import BlockBuilder
from dissector.app.live_capture import IDLE_FLUSH_LONG, silence_threshold
from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.framing.timing import LineTiming, silences_inside
from dissector.model import Chunk, Stamp
from dissector.pipeline import Dissector
from dissector.render.timefmt import Clock
from dissector.sim.simulate import encode_ascii, generate_session
from dissector.sources.serial_times import ByteTimedChunk, ReadClock

START = 1_796_400_000_000_000_000


def reads_of(records: list[tuple[bytes, float]], seed: int, byte_time: float, largest: int) -> list[tuple[bytes, Stamp]]:
    """Reads of the records (bytes, time of the first byte), with noise and a clock that steps back."""
    rng = random.Random(seed)
    reads: list[tuple[bytes, Stamp]] = []
    clock = 0.0
    shift = 0
    for number, (data, when) in enumerate(records):
        when -= records[0][1]
        if rng.random() < 0.05:
            data = bytes(rng.randrange(256) for _ in range(rng.randint(1, 30))) + data
        if rng.random() < 0.05:
            data += rng.choice([b"\x00", b"\xfe", b"\xff\xff"])
        if number == len(records) // 2:
            shift = -2_000_000_000  # NTP stepped the wall clock back 2 s
        when = max(when, clock)
        while when - clock > 0.010:
            clock += 0.010
            reads.append((b"", Stamp(int(clock * 1e6) * 1000 + START + shift)))
        at = 0
        while at < len(data):
            piece = data[at : at + rng.randint(1, largest)]
            at += len(piece)
            # (now and then a read later than the line: its first bytes back-dated before the previous read's stamp)
            clock = when + at * byte_time + (0.004 if rng.random() < 0.05 else rng.random() * 0.0003)
            reads.append((piece, Stamp(int(clock * 1e6) * 1000 + START + shift)))
    return reads


def rtu_records(seed: int) -> list[tuple[bytes, float]]:
    return generate_session(150, seed=seed)


def ascii_records(seed: int) -> list[tuple[bytes, float]]:
    return [(encode_ascii(data[0], data[1:-2]), when * 2.2) for data, when in generate_session(100, seed=seed)]


def said_of(item: object) -> tuple[object, ...]:
    """An item's every field (items compare by identity), its time as ns too."""
    return (type(item).__name__, item.time.ns,  # type: ignore[attr-defined]
            *((field.name, getattr(item, field.name)) for field in dataclasses.fields(item)))  # type: ignore[arg-type]


def fed(framer_type: type, baud: int, char_time: float, reads: list[tuple[bytes, Stamp]]) -> list[object]:
    """Both ways, read by read: the items (every field; times as ns) are the same; what the framers hold is
    the same where both decided as far (the whole read may decide noise further: its first bytes held, then
    their time, the safe time, is no earlier). The items, read by read."""
    whole, runs = framer_type(baud), framer_type(baud)
    whole_clock, runs_clock = ReadClock(char_time), ReadClock(char_time)
    said: list[object] = []
    for data, stamp in reads:
        chunk = whole_clock.chunk(data, stamp)
        items = [said_of(item) for item in (whole.feed(chunk) if chunk is not None else [])]
        assert items == [said_of(item) for chunk in runs_clock.chunks(data, stamp) for item in runs.feed(chunk)]
        said.append(items)
        # (either may have decided further: the whole read by the times of its bytes, the runs by their ends,
        # which bound a CRC scan as a record's do, reach.py _framed_reach; the items are the same)
        if whole.offset == runs.offset:
            assert (whole.held_since and whole.held_since.ns) == (runs.held_since and runs.held_since.ns)
            assert whole._boundaries == runs._boundaries  # the silences weighed (evidence of a frame's end)
    said.append([said_of(item) for item in whole.finish()])
    assert said[-1] == [said_of(item) for item in runs.finish()]
    return said


# (framer, its baud, the port's character time: 8E1, 8N1, 8N2, and one far longer than the line's t3.5)
CASES = [
    (RtuFramer, 19200, 11 / 19200, rtu_records, 64),
    (RtuFramer, 115200, 10 / 115200, rtu_records, 300),
    (RtuFramer, 9600, 11 / 9600, rtu_records, 8),
    (RtuFramer, 115200, 0.004, rtu_records, 16),
    (AsciiFramer, 9600, 10 / 9600, ascii_records, 40),
    (AsciiFramer, 19200, 0.6, ascii_records, 40),
]


@pytest.mark.parametrize(("framer_type", "baud", "char_time", "records", "largest"), CASES)
@pytest.mark.parametrize("seed", [1, 2])
def test_a_read_as_one_chunk_frames_as_its_runs_do(framer_type: type, baud: int, char_time: float, records,  # noqa: ANN001
                                                  largest: int, seed: int) -> None:
    said = fed(framer_type, baud, char_time, reads_of(records(seed), seed, char_time, largest))
    assert sum(len(items) for items in said) > 100  # type: ignore[arg-type]


def test_the_reads_hold_what_the_cases_are_for() -> None:
    """Bytes held at the floor, and a clock stepped back, happen in these reads; the long character
    marks silences inside reads."""
    reads = reads_of(rtu_records(1), 1, 11 / 19200, 64)
    clock = ReadClock(11 / 19200)
    held = stepped = 0
    previous = None
    for data, stamp in reads:
        chunks = clock.chunks(data, stamp)
        held += bool(chunks) and len(chunks) < len(data)
        stepped += previous is not None and stamp.ns < previous - 1_000_000_000
        previous = stamp.ns
    assert held >= 2 and stepped == 1
    # 4 ms a character on a 115200 line (t3.5 1.75 ms): a silence before each byte after the first
    chunk = ReadClock(0.004).chunk(bytes(4), Stamp(START))
    assert isinstance(chunk, ByteTimedChunk) and chunk.time == Stamp(START - 12_000_000)
    assert list(silences_inside(chunk.times, 100, LineTiming(115200))) == [101, 102, 103]  # type: ignore[arg-type]
    # 8N1's character on an 8E1 line: none
    chunk = ReadClock(10 / 115200).chunk(bytes(400), Stamp(START))
    assert list(silences_inside(chunk.times, 100, LineTiming(115200))) == []  # type: ignore[arg-type]


def test_the_silence_after_a_read_is_from_its_last_byte() -> None:
    """A read whose first bytes are held at the floor: the silence before the next read is counted from
    its last byte's time, as from the last of its runs (not from its first byte, the chunk's time)."""
    c = round(11e6 / 19200) * 1000  # ns a character, 8E1 (573 us)
    t35 = round(3.5 * 11e9 / 19200)
    for after, boundary in ((t35 + c + 2_000, True), (t35 + c - 2_000, False)):
        reads = [(b"\x01\x02\x03\x04", Stamp(START)), (bytes(range(10, 18)), Stamp(START + 2 * c)),
                 (b"\x05\x06", Stamp(START + 2 * c + after + c))]
        for whole in (True, False):
            framer, clock = RtuFramer(19200), ReadClock(11 / 19200)
            for data, stamp in reads:
                for chunk in [clock.chunk(data, stamp)] if whole else clock.chunks(data, stamp):
                    framer.feed(chunk)  # type: ignore[arg-type]
            assert (12 in framer._boundaries) is boundary
            assert framer.held_since == Stamp(START - 3 * c)


def reference_times(char_us: float, floor: int | None, data: bytes, stamp: Stamp) -> list[int]:
    """Each byte's ns as 4173324 wrote the rule: the stamp less round((last - k) * char_us) us, at least the floor."""
    last = len(data) - 1
    times = []
    for index in range(last + 1):
        ns = stamp.ns - round((last - index) * char_us) * 1000
        times.append(floor if floor is not None and ns < floor else ns)
    return times


@pytest.mark.parametrize("char_time", [11 / 19200, 10 / 115200, 11 / 921600, 11 / 11_000_000, 1e-6, 0.004])
def test_runs_and_byte_times_follow_the_rule(char_time: float) -> None:
    rng = random.Random(5)
    clock = ReadClock(char_time)
    at = START
    packed_reads = held = all_held = 0
    for _ in range(400):
        at += rng.choice([0, 1_000, 50_000, 2_000_000, 30_000_000, -3_000_000_000])
        data = bytes(rng.randint(0, 600) if rng.random() < 0.9 else 0)
        floor = clock.floor if clock.floor is None or at >= clock.floor else None
        times = clock.byte_times(data, Stamp(at))
        if not data:
            assert times is None
            continue
        expected = reference_times(clock.char_us, floor, data, Stamp(at))
        assert [times.ns(k) for k in range(len(data))] == expected
        assert times.at(0).ns == expected[0]
        starts, ns = clock.runs(times)
        runs = [(k, t) for k, t in enumerate(expected) if k == 0 or t != expected[k - 1]]
        assert list(zip(starts, ns)) == runs == list(times.runs())
        assert times.last_run() == runs[-1][0]
        offset = rng.randrange(1 << 40)
        packed = clock.packed(times, offset)
        if clock.char_us > 2:
            assert packed is not None
            assert [(start - offset, ns) for start, ns in zip(*packed)] == runs
            packed_reads += 1
            held += len(runs) < len(data)
            all_held += len(runs) == 1 < len(data)
        else:
            assert packed is None
    assert packed_reads > 300 or clock.char_us <= 2
    assert (held > 20 and all_held > 5) or clock.char_us <= 2


def builder_blocks(add_whole: bool, char_time: float, baud: int, reads: list[tuple[bytes, Stamp]], block_bytes: int):  # noqa: ANN201
    clock = ReadClock(char_time)
    builder = _ReadBlocks(LineTiming(baud)) if add_whole else BlockBuilder(LineTiming(baud))
    builder.block_bytes = block_bytes
    blocks = []
    for data, stamp in reads:
        if add_whole:
            times = clock.byte_times(data, stamp)
            if times is not None:
                blocks += builder.add_read(data, times, clock) or []  # type: ignore[attr-defined]
        else:
            for chunk in clock.chunks(data, stamp):
                blocks += builder.add(chunk)
    blocks += builder.flush()
    return [(block.data, list(block.starts), list(block.times), bytes(block.flags), block.exact,
             [block.chunk(index) for index in range(len(block.starts))]) for block in blocks]


@pytest.mark.parametrize(("char_time", "baud"), [(11 / 19200, 19200), (10 / 115200, 115200), (0.004, 115200)])
@pytest.mark.parametrize("block_bytes", [1 << 18, 1000])
def test_the_engine_blocks_of_a_read_at_once_are_those_of_its_runs(char_time: float, baud: int, block_bytes: int) -> None:
    reads = reads_of(rtu_records(3), 3, char_time, 64)
    whole = builder_blocks(True, char_time, baud, reads, block_bytes)
    assert whole == builder_blocks(False, char_time, baud, reads, block_bytes)
    assert sum(len(block[1]) for block in whole) > sum(len(data) for data, _stamp in reads) // 2
    flags = b"".join(block[3] for block in whole)
    assert flags.count(5) > 10  # timed, a silence before: the boundaries are weighed


def shown_of(item: object) -> tuple[object, ...]:
    """What a line of the item shows: its bytes, time, kind, number, answer and notes."""
    response = getattr(item, "response_ref", None)
    response = response() if response is not None else None
    return (type(item).__name__, item.offset, item.raw, item.time.ns, getattr(item, "kind", None),  # type: ignore[attr-defined]
            getattr(item, "number", None), getattr(item, "unanswered", None), getattr(response, "number", None),
            list(item.warnings), list(getattr(item, "notes", [])))  # type: ignore[attr-defined]


@pytest.mark.parametrize("summary", [True, False])
def test_the_engine_live_path_shows_the_same_either_way(summary: bool) -> None:
    reads = reads_of(rtu_records(4), 4, 11 / 19200, 64)
    shown = []
    for whole in (True, False):
        lines: list[object] = []
        dissector = Dissector(RtuFramer(19200), timeout=0.5)
        path = LivePath(dissector, None, Clock() if summary else None, lambda items: lines.extend(
            shown_of(item) for item in items), lines.append, 0.5, silence_threshold(19200),
            IDLE_FLUSH_LONG, summary, None, 11 / 19200)
        if not whole:
            def add(data: bytes, stamp: Stamp, path: LivePath = path) -> None:
                for chunk in path.clock.chunks(data, stamp):
                    for block in path.builder.add(chunk):
                        path.path.feed(block)
            path._add = add  # type: ignore[method-assign]
        now = 1000.0
        for data, stamp in reads:
            now += 0.002
            path.feed([(data, stamp, now)])
        path.finish()
        assert path.engine_items > 100
        shown.append(lines)
    assert shown[0] == shown[1]
    assert len(shown[0]) > 100
