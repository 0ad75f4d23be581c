"""The compiled summary path: plain summary lines of a raw RTU capture, at tshark's speed.

Profiling the Python stages (README, Performance) showed ~15 us a frame spread over every stage:
framing, pairing, decoding, annotation and the summary text each cost a few, and no hot spot was
left. What tshark does in 4 us a frame could only be matched by doing all of it in compiled code for
the transactions of a bus, so dissector/accel/_summary.c does exactly that for every public code the
protocol table marks compiled (both ways, and their exceptions; for FC17, FC20, FC21 and FC43 with
texts made here, `transaction_texts`), and hands the stream over to the Python stages, untouched, for
everything else; the list of what it hands back, and why, heads _summary.c (noise, damage, lengths
only a CRC scan finds but FC8's echoes, vendor codes, anything with a warning or a note, an exception that changes
the annotator's memory); inside a noise run the Python framer has open, the engine frames the noise
for it (_noise.h, skip_noise: random bytes cost 4 to 5 s a MB framed in Python). The Python stages
stay the reference: the Construct grammars, the annotator and the renderer; the compiled path asks them for every text it shows (register readings, function
names, exception explanations) and keeps the annotator's parameter memory up to date.
tests/differential/test_fastsummary.py holds its output equal to the Python stages' byte for byte.

The engine and this module exchange typed objects: `SlaveFacts` and `Texts` (read by attribute name
in C), a register's text and whether the annotator named it.

Used for plain summary output of untimed RTU input (raw files, stdin, --hex) with no filter,
statistics, pcap output or -c; VW3_PURE_PYTHON=1 turns it off. Without the C extension (no compiler at
install time) the Python stages do everything.
"""
from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from dissector.decode.fields import decode_frame
from dissector.devices.access import read_only_addresses
from dissector.devices.checks import unsupported_subfunctions
from dissector.model import Chunk, Frame, Item, Kind
from dissector.pipeline import Dissector
from dissector.render.describe import function_label, info_text, register_text
from dissector.render.summary import findings_text
from dissector.protocol import table

try:
    from dissector.accel import _summary
except ImportError:  # built without a C compiler, or from older sources: the Python stages do everything
    _summary = None  # type: ignore[assignment]

HANDLED = table.COMPILED  # function codes the compiled path decodes (_summary.c, through _tables.h), and their exceptions
EXPLAINED_MAX = 4096  # transactions' texts kept (bounded: memory stays flat)
_PLAIN_READS = table.plain_register_reads()  # an exception 2 to these may change the annotator's memory
WINDOW = 512  # bytes handed to the Python stages at a time while they have the stream
# Over noise and damaged frames, which the engine hands straight back, the Python stages frame up to
# a stride of bytes at a time (doubling from NOISE_STRIDE to NOISE_STRIDE_MAX) instead of one item at
# a time: past the noise's end they frame at most about as many bytes as the noise had, and 16 KiB.
NOISE_STRIDE = 16
NOISE_STRIDE_MAX = 16384
SHORT_STRETCH = 16  # items the engine numbers before it hands over again, below which
CALM_MAX = 32  # `calm` doubles (PythonSide)
NEED, HANDOVER = 0, 1


def available() -> bool:
    return _summary is not None and not os.environ.get("VW3_PURE_PYTHON")


def built() -> bool:
    """The extension is built from these sources (a build from older ones is not imported at all:
    its stamp is checked once, dissector/accel/__init__.py)."""
    return _summary is not None


@dataclass(frozen=True, slots=True)
class SlaveFacts:
    """What the engine must know of a slave to give the annotator's answers itself (read by name in C)."""

    usable: bool  # False: every transaction of this slave goes to the Python stages
    # Per handled function: its name as shown, and the request check: () none, the device's limits
    # (read quantity[, write quantity]), or None when every request must go to the annotator.
    functions: dict[int, tuple[str, tuple[int, ...] | None]] = field(default_factory=dict)
    mapped: frozenset[int] = frozenset()  # addresses the annotator names (asked of `piece`)
    depend: dict[int, tuple[int, frozenset[int]]] = field(default_factory=dict)  # bits_depend: (on, plain_when)
    sources: frozenset[int] = frozenset()  # the addresses bits_depend rules look at
    seen: dict[int, tuple[Any, ...]] | None = None  # the annotator's parameter memory, None: not tracked
    protected: int = -1  # the value a device reads for a protected parameter (16#8000), -1: none
    bases: dict[int, int] | None = None  # PLC-style display base per function, None: protocol addresses
    diagnostics: frozenset[int] = frozenset()  # FC8 sub-functions the profile explains (a note: Python's)
    # --stats: (address, value) -> (text, code) of a register as this slave's device names it now (a
    # profile change gives a new one); the engine asks it once per parameter, not once per value.
    namer: Callable[[int, int], tuple[str | None, str | None]] | None = None
    read_only: frozenset[int] = frozenset()  # read-only parameters: a write of one is warned (devices/access.py)


class PathEngine(_summary.Engine if _summary is not None else object):  # type: ignore[misc]
    """The compiled engine, its plain fields in the shapes its callers use: `expect` as the framer's
    (slave, function) or None, `clock` as the time column's (first, previous) ns or None each."""

    __slots__ = ()

    @property
    def expect(self) -> tuple[int, int] | None:
        return None if self.expect_slave < 0 else (self.expect_slave, self.expect_function)

    @expect.setter
    def expect(self, value: tuple[int, int] | None) -> None:
        self.expect_slave, self.expect_function = (-1, -1) if value is None else value

    @property
    def clock(self) -> tuple[int | None, int | None]:
        return (self.first_ns if self.has_first else None, self.previous_ns if self.has_previous else None)

    @clock.setter
    def clock(self, value: tuple[int | None, int | None]) -> None:
        first, previous = value
        self.has_first, self.first_ns = first is not None, first or 0
        self.has_previous, self.previous_ns = previous is not None, previous or 0

    def set_timing(self, char_time: float, t15: float, timeout: float | None, clock: int) -> None:
        """The line's character time and t1.5 (timing.LineTiming), the pairing timeout in seconds
        (None: none), the time column (0: -t r, 1: -t d or dd)."""
        self.char_time, self.t15, self.clock_format = char_time, t15, clock
        self.timeout = -1.0 if timeout is None else timeout


def make_engine(annotator: Any | None, shown: bool = True, pairer: Any | None = None) -> Any:
    """The compiled engine, told about devices by `annotator` (None: spec semantics only, as -n);
    `shown` False: nothing reads its lines (--stats alone), its transactions are only counted; told by
    `pairer` (pairing.py) which slaves are in Listen Only Mode."""
    plain = SlaveFacts(True, {function: (function_label(function, None), ()) for function in HANDLED})
    unknown = SlaveFacts(False)

    def slave_info(slave: int) -> SlaveFacts:
        if pairer is not None and pairer.in_listen_only(slave):
            return unknown  # (the engine keeps no mode: pairing.py notes the slave's requests)
        if annotator is None:
            return plain
        if not hasattr(annotator, "summary_facts"):  # an annotator the compiled path knows nothing of
            return unknown
        if not annotator.compilable(slave):
            # Profile `auto` still judges this slave's traffic (SummaryPath.forget_changed asks again
            # once it is settled), or its map has 32-bit values: its frames go through the annotator.
            return unknown
        checks, mapped, depend, sources, seen, protected, bases = annotator.summary_facts(slave, HANDLED)
        functions = {
            function: (function_label(function, special), check)
            for function, (special, check) in checks.items()
        }
        device = annotator.device(slave)
        explained = frozenset(device.profile.diagnostics) | unsupported_subfunctions(device.profile)
        return SlaveFacts(True, functions, mapped, depend, sources, seen, protected, bases, explained,
                          annotator.namer(slave), read_only_addresses(device))

    def piece(slave: int, function: int, address: int, value: int) -> tuple[str, bool]:
        register = annotator.plain_register(slave, function, address, value)
        return register_text(register), bool(register.code or register.text)

    texts = transaction_texts(annotator) if shown else counted_texts(annotator)
    return PathEngine(slave_info, piece, texts)


@dataclass(frozen=True, slots=True)
class Texts:
    """What the summary shows of a transaction, apart from numbers and pairing (read by name in C)."""

    request_info: str
    request_tail: str  # its notes and warnings, each ` [...]`
    response_info: str = ""
    response_tail: str = ""


def _tail(frame: Frame) -> str:
    # The summary's own budget: past 240 characters of notes, `[+N more notes]` (it showed them all).
    return findings_text(frame)


def _plain_end(info: str) -> bool:
    return bool(info) and 0x20 < ord(info[-1]) < 0x7F  # as the engine's own lines; else Python


def _scratch(raw: bytes, kind: Kind, offset: int = 0, request: Frame | None = None) -> Frame:
    crc = int.from_bytes(raw[-2:], "little")
    return Frame(offset, raw, None, kind, raw[0], raw[1] & 0x7F, crc, crc, request=request)


def transaction_texts(annotator: Any | None) -> Callable[[int, bytes, bytes | None], Texts | None]:
    """The engine's `texts` callback, for the transactions whose texts it does not make itself: those
    of the codes table.Compiled.texts names, and the exceptions answering the requests it shows. The
    Python stages decode and annotate a scratch pair of frames; the annotator keeps no state for these
    (an exception that would change it gets None, _texts), so the texts depend on the frames' bytes and
    the slave's profile alone and are kept by them (bounded)."""
    known: dict[tuple[str | None, bytes, bytes | None], Texts | None] = {}
    choosing = _choosing(annotator)

    def texts(slave: int, request_raw: bytes, response_raw: bytes | None) -> Texts | None:
        if _may_choose(annotator, slave, request_raw[1], choosing):
            return None
        key = (_profile_name(annotator, slave), request_raw, response_raw)
        if key in known:
            return known[key]
        found = _texts(annotator, slave, request_raw, response_raw)
        if len(known) >= EXPLAINED_MAX:
            known.clear()
        known[key] = found
        return found

    return texts


def _texts(annotator: Any | None, slave: int, request_raw: bytes, response_raw: bytes | None) -> Texts | None:
    """A transaction's texts as the summary shows them, or None where the engine must hand it over: an
    info that does not end in a plain character, or an exception after which the annotator would change
    its state: exception 2 to a read on a device that protects parameters (p.38) makes it forget the
    values of every parameter read (with an annotator the engine knows nothing of, every exception)."""
    exception = response_raw is not None and response_raw[1] & 0x80
    if exception and annotator is not None:
        if not hasattr(annotator, "profile_for"):
            return None
        if response_raw[2] == annotator.profile_for(slave).all_protected_exception and request_raw[1] in _PLAIN_READS:
            return None
    request = _scratch(request_raw, Kind.REQUEST)
    decode_frame(request)
    response = None
    if response_raw is not None:
        response = _scratch(response_raw, Kind.EXCEPTION if exception else Kind.RESPONSE, len(request_raw), request)
        decode_frame(response)
    if annotator is not None:
        annotator(request)
        if response is not None:
            annotator(response)
    found = Texts(info_text(request), _tail(request))
    if response is not None:
        found = Texts(found.request_info, found.request_tail, info_text(response), _tail(response))
    if not _plain_end(found.request_info) or (response is not None and not _plain_end(found.response_info)):
        return None
    return found


_COUNTED = Texts("-", "", "-", "")  # no line made: the transaction is counted (--stats alone)


def counted_texts(annotator: Any | None) -> Callable[[int, bytes, bytes | None], Texts | None]:
    """The `texts` callback of an engine whose lines nobody reads: transaction_texts' only effect on
    what is counted is to hand over what profile `auto` may still choose a profile by, and the
    exceptions it hands over; no scratch frames decoded and annotated for other texts nobody shows
    (the max-size mix's --stats asked 9,795)."""
    choosing = _choosing(annotator)
    exceptions = transaction_texts(annotator)

    def texts(slave: int, request_raw: bytes, response_raw: bytes | None) -> Texts | None:
        if response_raw is not None and response_raw[1] & 0x80:
            return exceptions(slave, request_raw, response_raw)
        return None if _may_choose(annotator, slave, request_raw[1], choosing) else _COUNTED

    return texts


def _may_choose(annotator: Any | None, slave: int, function: int, choosing: frozenset[int]) -> bool:
    """Profile `auto` may still change this slave's profile through this transaction: it goes to the
    Python stages, which see every frame that can. The engine shows only settled slaves, whose profile
    changes by an identification alone (selection.Selector._identified: `choosing`) or by an answer
    to a function their profile does not support, which the engine hands over before asking."""
    final = getattr(annotator, "final", None)
    return final is not None and function in choosing and not final(slave)


def _choosing(annotator: Any | None) -> frozenset[int]:
    """Function codes whose frames can identify a device: those only one device speaks, and Read Device
    Identification, whose answer names the product (the table's mei_response)."""
    selector = getattr(annotator, "selector", None)
    codes: set[int] = set()
    for profile, _rows in getattr(selector, "candidates", ()):
        codes |= profile.identifying_functions
    codes |= {entry.code for entry in table.FUNCTIONS if entry.response.name == "mei_response"}
    return frozenset(codes)


def _profile_name(annotator: Any | None, slave: int) -> str | None:
    """The slave's profile: texts kept by bytes are kept per profile (profile `auto` may change it)."""
    profile_for = getattr(annotator, "profile_for", None)
    return None if profile_for is None else profile_for(slave).name


class SummaryPath:
    """Drives the stream through the compiled engine and, where it hands over, the Python stages.

    The Python stages take the stream at the start of a transaction the engine would not show, frame
    one frame at a time, and give it back as soon as nothing is pending (no request awaiting its
    answer, no noise run open): both then agree on the item numbers and the framer's expectation.
    Over noise and damage they go on by strides (PythonSide).
    """

    def __init__(self, dissector: Dissector, annotator: Any | None, write_items: Callable[[list[Item]], None],
                 write_lines: Callable[[bytes], None], stats: Any | None = None) -> None:
        """`stats`: a compiled store (render/stats.py StatsCollector.engine_store) that the engine
        counts the transactions it shows into (--stats); the lines are then the caller's to drop."""
        self.dissector = dissector
        self.framer = dissector.framer
        self.pairer = dissector.pairer
        self.engine = make_engine(annotator, pairer=self.pairer)
        self.engine.stats = stats
        self.annotator = annotator
        self.write_items = write_items
        self.write_lines = write_lines
        self.buf = b""  # bytes not given to either side yet start at buf[pos], absolute offset base+pos
        self.base = 0
        self.pos = 0
        self.python = False  # the Python stages have the stream
        self.taken_at = 0  # where they took it
        self.side = PythonSide(dissector, write_items)

    def feed(self, data: bytes) -> None:
        if self.pos:
            self.base += self.pos
            self.buf = self.buf[self.pos :]
            self.pos = 0
        self.buf += data
        if self.python:
            self._python_frames()
        if not self.python:  # (and when they gave it back: the engine takes the rest of these bytes)
            self._engine_frames()

    def finish(self) -> None:
        if not self.python:
            self._hand_over()
        self.framer.pause_at(None)
        rest = self.buf[self.pos :]
        self.buf, self.pos = b"", 0
        self.write_items(self.dissector.feed(Chunk(rest)) + self.dissector.finish())

    def _engine_frames(self) -> None:
        while not self.python:
            lines, self.pos, status = self.engine.run(self.buf, self.pos)
            if lines:
                self.write_lines(lines)
            if status == NEED:
                return
            self._hand_over()
            self._python_frames()

    def _hand_over(self) -> None:
        self.taken_at = self.base + self.pos
        self.framer.restart_at(self.taken_at, self.engine.expect)
        self.pairer.count = self.engine.count
        self.side.take(self.engine.count)
        self.python = True

    def forget_changed(self) -> None:
        """Slaves whose device profile changed (or settled) while the Python stages had the stream are
        asked about again: the engine shows them from then on."""
        forget_changed(self.engine, self.annotator, self.pairer)

    def _python_frames(self) -> None:
        framer = self.framer
        side = self.side
        while True:
            if side.ready() and framer.offset > self.taken_at and self.pairer.idle:
                self.forget_changed()
                offset, rest, expect = framer.hand_back()
                start = offset - self.base
                if start >= 0 and start + len(rest) == self.pos:
                    self.pos = start  # the bytes not framed are still in buf: no copy of what follows
                else:
                    self.buf = rest + self.buf[self.pos :]
                    self.base, self.pos = offset, 0
                self.engine.count = self.pairer.count
                side.give(self.pairer.count)
                self.engine.expect = expect
                self.engine.glitchy = framer.glitchy  # (learnt by the framer alone: the engine hands glitches over)
                self.python = False
                return
            if side.step():
                continue
            if self.pos >= len(self.buf):
                return  # it needs bytes that have not come yet
            window = self.buf[self.pos : self.pos + (WINDOW if side.settled else max(WINDOW, side.stride))]
            self.pos += len(window)
            side.write(self.dissector.feed(Chunk(window)))


def forget_changed(engine: Any, annotator: Any | None, pairer: Any) -> None:
    """The engine asks slave_info again about the slaves whose device profile changed (or settled) or
    whose Listen Only Mode did (pairing.py) while the Python stages had the stream."""
    for changed in (getattr(annotator, "changed", None), pairer.listen_changed):
        if changed:
            for slave in changed:
                engine.forget(slave)
            changed.clear()


def _intact(item: Item) -> bool:
    """A frame whose check is good (not noise, not damaged)."""
    return type(item) is Frame and item.crc_ok


class PythonSide:
    """The Python stages while they have the stream (SummaryPath, timedpath.TimedPath): they frame it
    one item at a time, so that the engine takes it back at their first idle point, where both agree
    on the item numbers and the framer's expectation. Noise and damaged frames the engine would hand
    straight back: inside a noise run the engine frames the noise for them (skip_noise), elsewhere they
    frame by strides of bytes (NOISE_STRIDE, doubling up to NOISE_STRIDE_MAX), and give the stream back only after `calm` intact frames in a row, which doubles (up to CALM_MAX)
    each time the engine then numbered fewer than SHORT_STRETCH items before handing it over
    again (noise every few frames: each hand-over costs more than the frames it saves). Any idle point
    would do for the output, since both sides decide alike; these only save calls and hand-overs."""

    __slots__ = ("dissector", "framer", "write_items", "settled", "stride", "calm", "run", "damaged", "back", "noisy",
                 "frame_noise")

    def __init__(self, dissector: Dissector, write_items: Callable[[list[Item]], None]) -> None:
        self.dissector = dissector
        self.framer = dissector.framer
        self.write_items = write_items
        self.settled = True  # `calm` intact frames since the last noise or damaged frame (or none of those)
        self.stride = NOISE_STRIDE
        self.calm = 1
        self.run = 0  # intact frames in a row since the last noise or damaged frame
        self.damaged = False  # this stretch of the Python stages had noise or a damaged frame
        self.back = -1  # the engine's item count when it last took the stream back after damage
        self.noisy = False  # the engine's last skip_noise took bytes: the framer takes one item at a time
        # Live (livepath.py) the line's speed bounds the noise, and -w joins a noise run to the damaged frame
        # after it only within one batch of items (app/live_capture.py _records), which items out one at a
        # time would part: there the framer frames noise by strides, as before the engine framed it.
        self.frame_noise = True

    def take(self, count: int) -> None:
        """They take the stream from the engine, whose item count is `count`."""
        if self.back >= 0:
            self.calm = min(2 * self.calm, CALM_MAX) if count - self.back < SHORT_STRETCH else 1
            self.back = -1
        self.settled = True
        self.damaged = False
        self.stride = NOISE_STRIDE
        self.noisy = False

    def give(self, count: int) -> None:
        """They give the stream back, the item count being `count`."""
        if self.damaged:
            self.back = count

    def ready(self) -> bool:
        """May the engine take the stream back at this point, if framer and pairer are idle? Not in
        noise (a run open, or the last item) nor soon after a damaged frame."""
        return self.settled and self.framer.idle

    def step(self) -> bool:
        """One frame (or one noise run's next bytes), or up to a stride of bytes while not ready(),
        with the bytes the framer holds: did it advance? In an open noise run the engine takes the
        bytes it finds to be noise first (skip_noise); where it stops, the framer decides one position,
        and in noise (`noisy`: the engine's last call took bytes) one item after it, so that the engine
        goes on with the noise after a damaged frame."""
        framer = self.framer
        before = framer.offset
        if (self.settled or self.noisy) and framer.idle:
            framer.pause_at(before + 1)
        elif self.frame_noise and (skipped := skip_noise(framer)) is not None and (skipped[0] or skipped[1]):
            self.noisy = skipped[0] > 0 or self.noisy
            self.stride = NOISE_STRIDE  # (past the noise, again a few bytes at a time in Python)
            if skipped[1]:
                # (the framer's decision there waits for bytes to come too: it takes none before the engine asks
                # again; a later one would differ live, where a silence or a request's timeout may come first)
                framer.pause_at(framer.offset)
                return False
            framer.pause_at(framer.offset + 1)  # (where the engine stopped: the framer's own decision)
        else:
            # (a short run, glitch bytes before a frame: strides, as the frames after it are the Python stages' too)
            self.noisy = False
            framer.pause_at(before + self.stride)
            if self.stride < NOISE_STRIDE_MAX:
                self.stride *= 2
        self.write(self.dissector.feed(Chunk(b"")))
        return framer.offset != before

    def write(self, items: list[Item]) -> None:
        """Items of the Python stages, out; counts the intact frames in a row."""
        if not items:
            return
        if self.settled:
            last = items[-1]
            if not _intact(last):
                self.settled = False
                self.damaged = True
                self.run = 0
                self.stride = NOISE_STRIDE
        else:
            run = 0
            for item in reversed(items):
                if not _intact(item):
                    self.run = 0
                    break
                run += 1
            self.run += run
            if self.run >= self.calm:
                self.settled = True
        self.write_items(items)


def skip_noise(framer: Any) -> tuple[int, bool] | None:
    """The engine frames the noise an RTU framer's open run goes on with (framing/rtu.py take_noise, _noise.h
    noise_span): how many bytes it took and whether where they end waits for bytes; None where it does not."""
    if _summary is None or framer.mode != "rtu":
        return None
    return framer.take_noise(_summary.noise_span)


def summarize(chunks: Iterable[Chunk], path: SummaryPath, after_chunk: Callable[[], None]) -> None:
    for chunk in chunks:
        path.feed(chunk.data)
        after_chunk()
    path.finish()
    after_chunk()
