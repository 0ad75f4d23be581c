"""Modbus RTU framer: a byte stream in, frames and noise out.

An RTU frame is `slave | function | data | CRC-16 (low byte first)`, at most 256 bytes (a longer one whose
header gives its length, up to rules.MAX_COUNTED, is a frame when its CRC is good, with a warning). On the wire,
frames are separated by a silence of 3.5 character times, but a listen-only tap seldom keeps that
information: a raw capture has no timestamps at all, and USB serial adapters deliver bytes in bursts
(FTDI: 16 ms latency timer), so a request and its response may arrive in one read and a long response
in several. Gaps, record ends and line ends are therefore evidence here, never cuts.

Each function code's length rules are applied in both directions (a read request is 8 bytes; its
response is 5 + byte count; a FC16 request is 9 + byte count, or 9 + 2 x quantity when the two
disagree, as in the Altivar 212 manual's example...), and the CRC confirms the choice. Length rules
come first: a CRC-only framer accepts `01 04 02 03 01 78` as a frame because that 6-byte prefix of the
7-byte response `01 04 02 03 01 78 00` happens to carry a valid CRC. Where both a request and a
response layout fit, the expectation decides: after a request to slave S with function F, a frame
from S with F is its response, if it repeats what the spec has an answer echo ([pairing] echo: an FC8
sub-function; an FC8 frame that does not is the master's next request, the same shape). Function
codes whose data has no length rule (FC8 sub-function 0, FC43 MEI 13, user-defined and vendor codes)
are found by scanning for the shortest length with a valid CRC, and an FC43/14 object list that does
not end in a valid CRC (a device that declares more objects than it sends) by one from its start.
Any address is framed: 248..255 are reserved (pymodbus uses 254 and 255), the decoder warns.

CRC-16/MODBUS has no final XOR, so a frame whose CRC high byte is 00 (1 frame in 256) also checks
without that last byte, and any frame followed by a 00 checks one byte longer: when two layouts
check out, a record boundary, else the one an intact frame follows, wins. A line that keeps leaving
00 glitches after frames is learnt (StreamFramer.glitchy: frames after glitch runs with a 00, less
those after other noise): there a 00 after a frame is a glitch, and the shortest reading the line
confirms wins (1 frame in 256 whose CRC ends in 00 is then shown a byte short: the bench counts them).

The evidence a real line gives, weighed where a frame with a good CRC is found (the rule):
- Anchors. Where a frame is expected to start, its CRC is enough: right after a frame (in step), at
  a record boundary (pcap records, hex-dump lines, --hex arguments) or after a silence of t3.5 or
  more between timed chunks (live reads), and after nothing but glitch bytes since one of those. A
  glitch byte is what a short low pulse on an idle line reads as (FF << k: FF FE FC ... 80 00): a bus
  driver's turn-around leaves one after frames (00 after requests, FE after responses on the
  sigrok-dumps wizmodbus line), a break reads as 00.
- The answer awaited (its slave and function) counts on its CRC wherever it starts.
- A glitch byte that is no device's address (00, F8, FC, FE, FF) followed by an intact frame is a
  glitch, whatever reading starting at it checks: an idle FF before every frame would otherwise make
  a reserved slave 255 pass a CRC once in 65,536 frames.
- Elsewhere (resynchronising inside noise: each position tried is a 1 in 65,536 chance of a random
  CRC match) a frame counts when the line confirms it: the end of the input, a boundary or silence, or
  an intact frame right after it or after glitch bytes (at most GLITCH_SKIP); for a request, also a
  frame of its slave after it (its answer, even damaged: a good request is never lost because its
  answer is), or fields only a real request has (a read of 1..125 registers, a coil set ON or OFF:
  evidence.plausible_request). So a CRC-valid frame is never lost to what follows it when an anchor,
  the expectation or its own fields speak for it; random bytes need two chances in 65,536 at once.
- A damaged frame (no layout checks out) is shown once, with its bad CRC, when its length is known,
  the line confirms its end as above (the end of the input only for the answer awaited), its address
  is a device's (1..247, or 0 with a function a broadcast may carry), it does not start with a glitch
  byte before a frame, and it holds no intact frame inside (a cut frame must not swallow the frames
  after it; where records are frames, this one's or the next, none crossing its record's end). The
  answer awaited cut by the end of the capture is noise whose reason says so ("the capture ends
  inside the response (8 of 9 bytes)"), never a frame of another kind.
Otherwise the byte is noise and the framer resynchronises. Measured by bench/noise_accuracy.py (see
README.md, Framing real lines): recovery and invented frames per kind of noise. Noise runs are
emitted in items of at most NOISE_ITEM_MAX bytes so that memory stays bounded on a garbage input.

The framer is a push parser (`feed` / `finish`) with no I/O of its own: files, pcap records and live
serial reads all drive the same object, and the answer does not depend on how the stream is split
(boundaries and times are part of the input, not of the split).
"""
from __future__ import annotations

from collections.abc import Callable

from dissector.protocol.crc import crc16, crc_lengths
from dissector.model import Frame, Item, Kind
from dissector.framing.bounded import NO_FRAME, TOO_SHORT, Bounded
from dissector.framing.reach import RecordEnds
from dissector.framing.evidence import plausible_request as _plausible_request
from dissector.framing.rules import (  # noqa: F401 (re-exported: the framer's tables, by their old home)
    MAX_ADU,
    MAX_COUNTED,
    MIN_ADU,
    MAX_SLAVE,
    NEED,
    NONE,
    LengthRule,
    Scan,
    _crc_ok,
    length_rule,
    quantity_rule,
    RULES,
    BY_QUANTITY,
    OTHER_FUNCTIONS,
    REQUEST_FIRST,
    RESPONSE_FIRST,
    Awaiting,
    _POSSIBLE_START,
    GLITCH_SKIP,
    NOT_BROADCAST,
    GLITCH_ADDRESSES,
    _REQUEST_FIRST_FAST,
    _SPECIAL,
    _RESPONSE_FIRST_FAST,
)
from dissector.framing.stream import GLITCH_BYTES, NOISE_ITEM_MAX, StreamFramer
from dissector.protocol import table
from dissector.protocol.rules import text

# (function code, kind) -> the length of a layout whose length is a byte count's (protocol table Counted) when
# that count is 0: every count of the spec counts something (a read's quantity is 1 or more, a write's too, a
# FIFO's count word...), so a reading with a bad CRC that counts nothing is no frame but the start of another
# one (a request cut by the end of the capture, '01 03 00 00 00', read as an answer with byte count 0).
_COUNTS_NOTHING = {
    (code, kind): layout.length.extra
    for code, request, response in table.known_layouts()
    for kind, layout in ((Kind.REQUEST, request), (Kind.RESPONSE, response))
    if isinstance(layout.length, table.Counted)
}


def _counts_nothing(buf: bytearray, i: int, kind: Kind, length: int) -> bool:
    """Is the reading (kind, length) at i a counted layout whose count is 0 (_COUNTS_NOTHING)?"""
    return _COUNTS_NOTHING.get((buf[i + 1], kind)) == length

# A repeated pattern (a line stuck on one value, a babbling device: 0C 0C 0C..., 01 03 01 03...) makes
# every position a possible frame start weighed in full (_match: layouts, CRCs, what follows): ~50 times
# the cost per byte of random bytes, which the regular expression skips. A position's decision reads the
# bytes of REPEAT_WINDOW from it at most (a CRC scan's frame, then glitch bytes and a frame after it: 2 x
# MAX_ADU + GLITCH_SKIP, with margin), so where the bytes repeat with a period, a position decides as the
# one a period before it did, under the same framer state (_repeats).
REPEAT_WINDOW = 3 * MAX_ADU
REPEAT_PROBE = 16  # bytes the period is found by (the last ones decided, found again up to MAX_ADU back)


class RtuFramer(RecordEnds, Bounded, Awaiting, StreamFramer):
    """Push parser: feed chunks, collect items. Items come out in stream order, unnumbered."""

    mode = "rtu"

    def take_noise(self, span: Callable[..., tuple[int, bool]]) -> tuple[int, bool] | None:
        """Add to the open noise run the bytes from the buffer's start that _run would take as noise, as `span`
        decides them from this framer's state (the engine's accel/_noise.h noise_span: random bytes framed
        here cost 4 to 5 s a megabyte): the buffer, the room left under NOISE_ITEM_MAX (no item given out:
        _run cuts it), the answer awaited, the record ends and starts. How many bytes it added (0: none) and
        whether the decision where they end waits for bytes to come; None where it does not decide: no run
        open, a silence in the buffer (_run weighs it), the run at its largest."""
        if not self._noise or self._silences:
            return None
        limit = min(len(self._buf), NOISE_ITEM_MAX - 1 - len(self._noise))
        if limit <= 0:
            return None
        slave, function = self._expect if self._expect is not None else (-1, -1)
        end, wait = span(self._buf, limit, slave, function, self._echo, self.glitchy, self._base,
                         list(self._boundaries), list(self._record_starts))
        if end:
            self._add_noise(0, end, NO_FRAME, [])
            self._consume(end)
        return end, wait

    def _valid_frame_at(
        self, buf: bytearray, i: int, n: int, final: bool, scan: bool = True
    ) -> bool | None:
        """Does an intact frame start at i? None when more bytes are needed to know.

        With scan=False only layouts with a length rule count (no CRC scan for the others).
        """
        if n - i < MIN_ADU:
            return None if not final else (i == n)
        undecided = False  # a CRC scan found nothing yet, but a longer frame may still arrive
        for _kind, rule in self._interpretations(buf, i):
            length = rule(buf, i, n)
            if type(length) is Scan:
                if scan:
                    reach = self._framed_reach(buf, i, n) if self._boundaries else n  # (up to it all has come)
                    if self._shortest_crc(buf, i, reach, length):
                        return True
                    undecided = undecided or (not final and reach == n and n - i < MAX_ADU)
                continue
            if length == NEED:
                if final or not self._crosses_framed_record(buf, i, length, n):
                    return None if not final else False
                continue  # (bytes that would swallow a record that is a frame: none, not waited for)
            if length < MIN_ADU or length > MAX_COUNTED:
                continue
            if i + length > n:
                if final or self._crosses_framed_record(buf, i, length, n):
                    continue
                return None
            if _crc_ok(buf, i, length):
                return True
        return None if undecided else False

    def _followed(self, buf: bytearray, end: int, n: int, final: bool, at_end: bool = True) -> bool | None:
        """Does the line say a frame ends at `end`? The end of the input (unless at_end is False), a
        record or burst boundary (or a silence), or an intact frame, right there or after a few glitch
        bytes. None: the bytes that tell have not come yet."""
        j = end
        while True:
            if final and j == n:
                # (live closes the bytes at a silence, finish(silence=True): a boundary, as a file of its reads has)
                return at_end or self._cut_by_silence
            if self._boundary_at(j):
                return True
            found = self._valid_frame_at(buf, j, n, final)
            if found or found is None:
                return found
            if j < n and buf[j] in GLITCH_BYTES and j - end < GLITCH_SKIP:
                j += 1
                continue
            return False

    def _answered(self, buf: bytearray, i: int, end: int, n: int, final: bool) -> bool | None:
        """Does a frame of the same slave start at `end` (after glitch bytes), damaged or not: the
        answer to a request, the next request to a slave? 1 chance in 256 x 16 for random bytes."""
        slave = buf[i]
        j = end
        while j - end <= GLITCH_SKIP:
            if n - j < 2:
                return None if not final else False
            if buf[j] == slave and _POSSIBLE_START.match(buf, j):
                return True
            if buf[j] not in GLITCH_BYTES:
                return False
            j += 1
        return False

    def _anchored(self, i: int) -> bool:
        """Is i where a frame is expected to start: right after a frame (in step), at a record or
        burst boundary or after a silence, or after nothing but glitch bytes since one of those?"""
        return not self._noise or self._glitches_only or self._boundary_at(i)

    @staticmethod
    def _shortest_crc(buf: bytearray, i: int, n: int, minimum: int) -> int:
        lengths = crc_lengths(buf, i, minimum, min(n - i, MAX_ADU))
        return lengths[0] if lengths else 0

    def _scan(self, buf: bytearray, i: int, n: int, minimum: int, final: bool) -> int:
        """A frame without a length rule: the shortest CRC match that the line confirms (_followed:
        an intact frame, the end, a boundary, after glitch bytes or not). A CRC scan alone would take
        noise for frames: each length tried is a 1 in 65,536 chance of a match. (The following frame
        also settles the 00 case of _match.) It does not reach across a record that is a frame of its own
        (_framed_reach).
        """
        reach = self._framed_reach(buf, i, n) if self._boundaries else n
        lengths = crc_lengths(buf, i, minimum, min(reach - i, MAX_ADU))
        # First a frame (or the end) right after it; only then one after glitch bytes: a frame followed
        # by a 00 checks one byte longer too (no final XOR). On a line that leaves glitches (glitchy),
        # the 00 is one: the shortest length the line confirms, glitch bytes skipped, wins.
        for glitches in ((True,) if self.glitchy else (False, True)):
            for length in lengths:
                if glitches:
                    following = self._followed(buf, i + length, n, final)
                else:
                    # (a record's end right after it settles as a frame there would)
                    following = self._boundary_at(i + length) or self._valid_frame_at(buf, i + length, n, final)
                if following is None:
                    return NEED
                # In step (right after a frame) a scanned frame is trusted over a short frame that may
                # check by chance inside it; while resynchronising, an intact frame inside wins.
                if following:
                    inside = self._noise and self._framed_inside(buf, i, length, n, final)
                    if inside is None:
                        return NEED
                    if not inside:
                        return length
        # (up to a record that is a frame, every byte has come: nothing longer to wait for)
        return NEED if reach == n and n - i < MAX_ADU and not final else NONE

    def _match(self, buf: bytearray, i: int, n: int, final: bool) -> tuple[Kind, int, bool] | int:
        """(kind, length, crc_ok) for a frame at i, NEED, or NONE when i starts no frame."""
        slave, function = buf[i], buf[i + 1]
        if slave in GLITCH_ADDRESSES:
            after = self._valid_frame_at(buf, i + 1, n, final)
            if after is None:
                if not self._ends_record(buf, i, n):
                    return NEED
            elif after:
                return NONE  # a glitch byte before a frame
        valid: list[tuple[Kind, int]] = []
        damaged: list[tuple[Kind, int]] = []
        waiting: list[int] = []  # lengths of layouts whose bytes have not all arrived (NEED: unknown)
        awaited = self._awaited(buf, i)
        for kind, rule in self._interpretations(buf, i):
            length = rule(buf, i, n)
            if type(length) is Scan:
                found = self._scan(buf, i, n, length, final)
                if found == NEED:
                    waiting.append(NEED)
                elif found:
                    valid.append((kind, found))
                elif MIN_ADU <= length.declared <= min(MAX_ADU, n - i):
                    damaged.append((kind, length.declared))  # (the length its fields give, its CRC bad)
                continue
            if length != NEED and (length < MIN_ADU or length > MAX_COUNTED):
                continue
            if length == NEED or i + length > n:
                if not final and not self._crosses_framed_record(buf, i, length, n):
                    waiting.append(length)
                continue
            if _crc_ok(buf, i, length):
                valid.append((kind, length))
            elif length <= MAX_ADU and not _counts_nothing(buf, i, kind, length):  # (over it: a good CRC only)
                damaged.append((kind, length))
        if len(valid) == 1:
            kind, length = valid[0]
            # CRC-16/MODBUS has no final XOR: a frame followed by a 00 byte also checks as a frame one
            # byte longer. Unless this is the answer awaited (preferred below too, whatever follows),
            # wait when a layout one byte longer may still arrive.
            expected = kind is Kind.RESPONSE and awaited
            if (
                not expected
                and not self._boundary_at(i + length)  # the record ends here: nothing longer
                and any(other == NEED or other == length + 1 for other in waiting)
            ):
                return NEED
            return (kind, length, True)
        if valid:
            # Two layouts check out (the 00 case above, mostly): on a line that leaves 00 glitches the
            # shortest reading it confirms, else a record boundary, else what follows, decides.
            if self.glitchy:
                # (a 00 after a frame is a glitch there, not the last byte of a longer frame; a record's
                # end after the glitch confirms the shorter reading)
                for kind, length in sorted(valid, key=lambda choice: choice[1]):
                    following = self._followed(buf, i + length, n, final)
                    if following is None:
                        return NEED
                    if following:
                        return (kind, length, True)
            for kind, length in valid:
                if self._boundary_at(i + length):
                    return (kind, length, True)
            if awaited and valid[0][0] is Kind.RESPONSE:
                # The answer awaited beats a reading one byte longer that the 00 after it makes check;
                # it is also what the shortcut above takes when the 00 has not arrived yet.
                return (*valid[0], True)
            for kind, length in valid:
                following = self._valid_frame_at(buf, i + length, n, final)
                if following is None:
                    return NEED
                if following:
                    return (kind, length, True)
            return (*valid[0], True)
        if waiting or slave > MAX_SLAVE or (slave == 0 and function in NOT_BROADCAST):
            # (a reserved address counts with a good CRC only: a glitch byte is one too; so does a
            # broadcast the spec does not allow, a read: 00 is a glitch byte)
            return NEED if waiting else NONE
        if slave in GLITCH_BYTES:
            # A glitch byte before a frame (a CRC scan's too, which _intact_inside does not try): no
            # damaged frame. (Broadcast and reserved glitch bytes were weighed above.)
            after = self._valid_frame_at(buf, i + 1, n, final)
            if after is None:
                return NEED
            if after:
                return NONE
        # No layout checks out: a damaged frame is shown once if the line says it ends where it would
        # (an intact frame, a boundary, after glitch bytes or not) and it holds no intact frame inside
        # (a cut frame must not swallow the intact frame that follows it).
        for kind, length in damaged:
            if self._crosses_framed_record(buf, i, length, n):
                continue
            # (the end of the input says little of a damaged frame: the awaited answer's only)
            following = self._followed(buf, i + length, n, final, awaited)
            if following is None:
                return NEED
            if following:
                inside = self._framed_inside(buf, i, length, n, final)
                if inside is None:
                    return NEED
                if inside:
                    continue
                return (kind, length, False)
        return NONE

    def _cut_answer(self, buf: bytearray, i: int, n: int) -> str | None:
        """At the end of the input: do bytes i..n begin the answer awaited, cut by the end of the
        capture? The reason to show them with, or None."""
        if n - i < 2 or not self._awaited(buf, i):
            return None
        # (the answer's reading, unless it counts nothing or is not as long as the request implies: then the
        # next, a request repeated before the answer, or the next one)
        for kind, rule in self._interpretations(buf, i):
            length = rule(buf, i, n)
            if type(length) is Scan:
                break
            if not (_counts_nothing(buf, i, kind, length) or self._not_the_answer(kind, length)):
                break
        else:
            return None
        longest = MAX_COUNTED  # (a length rule's reach, over MAX_ADU too: _match takes such a frame whole)
        if type(length) is Scan:
            # (a rule with a CRC fallback: cut only when the bytes there hold no frame a scan finds)
            if length.declared == NONE or self._scan(buf, i, n, length, True):
                return None
            length, longest = length.declared, MAX_ADU
        if length != NEED and not n - i < length <= longest:
            return None
        if self._intact_inside(buf, i, n - i, n, True):
            return None
        return self._cut_reason(kind, f"{n - i} of {length} bytes" if length != NEED else f"{n - i} bytes of it")

    def cut_answer(self, data: bytes) -> str | None:
        """Would `data`, fed now and ended there, be the answer awaited cut by the end of the capture
        (`--hex` asks before taking a short answer for a typo)? The reason, or None."""
        buf = bytearray(data)
        return self._cut_answer(buf, 0, len(buf)) if not self._buf else None

    def _confirmed(self, buf: bytearray, i: int, kind: Kind, length: int, n: int, final: bool) -> bool | None:
        """May a CRC-valid frame found away from any anchor (inside noise) count? Random bytes pass a
        CRC once in 65,536 tries per layout, so it needs the line's word too: what follows it
        (_followed), or, for a request, a frame of its slave right after it (its answer, even
        damaged)."""
        end = i + length
        following = self._followed(buf, end, n, final)
        if following is not False:
            return following
        if kind is Kind.REQUEST and buf[i] != 0:
            if _plausible_request(buf, i, length):
                return True
            return self._answered(buf, i, end, n, final)
        return False

    def _repeats(self, buf: bytearray, i: int, since: int, n: int, stop: int) -> tuple[int, int]:
        """Positions since..i-1 were all noise, decided with this _run's buffer under the framer's state of
        now (the caller's). If the bytes from some period p (<= MAX_ADU) before i repeat with period p, a
        position k from i on decides as k - p did, as long as its REPEAT_WINDOW holds no boundary and lies
        in the repetition and the buffer. (noise to i..end: its end, at most `stop`; the index before which
        trying again finds no more)."""
        found = buf.rfind(buf[i - REPEAT_PROBE : i], max(since, i - REPEAT_PROBE - MAX_ADU), i - 1)
        if found < 0:
            return i, i + 4 * REPEAT_PROBE  # (random bytes: trying at every position cost them a third more)
        period = i - REPEAT_PROBE - found
        first = i - period  # (>= since: positions first..i-1 have decided)
        limit = min(n, stop + REPEAT_WINDOW)
        if self._boundaries:
            # (none inside the windows: the stream's record ends and silences are evidence)
            after = self._boundaries.first_after(self._base + first - 1, self._base + limit)
            limit = limit if after is None else after - self._base
        # The repetition's end: buf[x] == buf[x + period] for x from first up to end - period.
        end, step = i, REPEAT_WINDOW
        while end < limit:
            step = min(step, limit - end)
            if buf[end - period : end - period + step] == buf[end : end + step]:
                end += step
                step *= 2
                continue
            low, high = 0, step  # (bytes end..end+low repeat, end..end+high do not)
            while high - low > 1:
                middle = (low + high) // 2
                if buf[end - period : end - period + middle] == buf[end : end + middle]:
                    low = middle
                else:
                    high = middle
            end += low
            break
        last = end - REPEAT_WINDOW  # (the last position whose window lies in the repetition)
        if last < i:
            return i, max(i + 1, end)
        return (stop, stop) if last + 1 >= stop else (last + 1, end)

    def _run(self, final: bool) -> list[Item]:
        buf = self._buf
        n = len(buf)
        i = 0
        items: list[Item] = []
        paused_from = n if self._pause is None else max(0, self._pause - self._base)
        # Positions since..i-1 decided as noise under the framer's state of now (_repeats); -1: none.
        since, retry, cut, only = -1, 0, False, False
        while n - i >= MIN_ADU or (final and i < n):
            if i >= paused_from:
                break
            if n - i < MIN_ADU:
                stop, reason = self._silence_cut(buf, i, n) or (n, self._cut_tail(buf, i, n) or TOO_SHORT)
                self._add_noise(i, stop, reason, items)
                i = stop
                continue
            # (the answer awaited and the line's glitchiness change with a frame only, which ends the noise)
            if not self._noise or final:
                since = -1
            elif since < 0 or self._noise_cut != cut or self._glitches_only != only:
                since, cut, only = i, self._noise_cut, self._glitches_only
            elif i >= retry and i - since >= REPEAT_PROBE:
                # (the noise item cut at NOISE_ITEM_MAX changes the state: a decision after it is made anew)
                end, retry = self._repeats(buf, i, since, n, min(paused_from, i + NOISE_ITEM_MAX - len(self._noise)))
                if end > i:
                    self._add_noise(i, end, NO_FRAME, items)
                    i = end
                    continue
            # Fast path: the likeliest interpretation checks out (nearly every frame of a clean bus).
            slave = buf[i]
            function = buf[i + 1]
            # (the answer awaited: its slave and function, and its echo where one is due, _awaited)
            awaited = self._expect == (slave, function & 0x7F) and (
                not self._echo or function & 0x80 or self._awaited(buf, i)
            )
            first = (_RESPONSE_FIRST_FAST if awaited else _REQUEST_FIRST_FAST).get(function)
            if first is None:
                taken = self._take_bounded(buf, i, n, final, items)  # (a run the line bounds, bounded.py)
                if taken == NEED:
                    break
                if taken:
                    i += taken
                    continue
                # No frame starts here: skip at C speed to the next byte pair that could start one.
                found = _POSSIBLE_START.search(buf, i + 1)
                end = found.start() if found is not None else (n if final else n - 1)
                self._add_skipped(i, end, items)
                i = end
                continue
            if (
                not self._noise
                and (first[0] is not Kind.EXCEPTION or awaited)
                and slave not in GLITCH_ADDRESSES  # (weighed by _match: a glitch byte before a frame?)
            ):
                kind, length, rule = first
                if not length:
                    length = rule(buf, i, n)
                # A next byte of 00 may belong to a longer frame (see _match): take the careful path.
                if type(length) is int and MIN_ADU <= length <= MAX_ADU and i + length < n and buf[i + length]:
                    stop = i + length - 2
                    crc = buf[stop] | buf[stop + 1] << 8
                    if crc16(buf[i:stop]) == crc:
                        offset = self._base + i
                        items.append(
                            Frame(
                                offset,
                                bytes(buf[i : i + length]),
                                self._time_at(offset) if self._timed else None,
                                kind,
                                slave,
                                function & 0x7F,
                                crc,
                                crc,
                                tail=self._tail_at(offset + length, offset) if self._timed else None,
                            )
                        )
                        # (awaits_answer: not a broadcast, not a request the spec has no server answer)
                        self._await_after(items[-1])
                        self._noise_cut = False
                        i += length
                        continue
            if final:
                cut = self._cut_tail(buf, i, n)
                if cut is not None:
                    # (noise: up to a silence inside that cuts them first, as live closed them there)
                    stop, cut = self._silence_cut(buf, i, n) or (n, cut)
                    taken = self._take_bounded(buf, i, n, final, items)  # (a run the line bounds wins)
                    if not taken:
                        self._add_noise(i, stop, cut, items)
                    i = i + taken if taken else stop
                    continue
            match = self._match(buf, i, n, final)
            if match == NEED:
                break
            if match == NONE or not match[2]:  # (no layout checks out: a run the line bounds wins, bounded.py)
                taken = self._take_bounded(buf, i, n, final, items)
                if taken == NEED:
                    break
                if taken:
                    i += taken
                    continue
            if match == NONE:
                # (bytes up to a silence that begin a frame it cuts: their reason, as live's, _silence_cut)
                stop, reason = self._silence_cut(buf, i, n) or (i + 1, self._no_frame(i))
                self._add_noise(i, stop, reason, items)
                i = stop
                continue
            kind, length, crc_ok = match  # type: ignore[misc]
            awaited = awaited and kind is not Kind.REQUEST
            if crc_ok and not awaited and not self._anchored(i):
                # Resynchronising inside noise: random bytes pass a CRC 1 time in 65,536 per layout
                # tried, so such a frame counts only when the line confirms it (_confirmed).
                following = self._confirmed(buf, i, kind, length, n, final)
                if following is None:
                    break
                if not following:
                    self._add_noise(i, i + 1, self._no_frame(i), items)
                    i += 1
                    continue
            raw = bytes(buf[i : i + length])
            offset = self._base + i
            frame = Frame(
                offset=offset,
                raw=raw,
                time=self._time_at(offset),
                kind=kind,
                slave=slave,
                function=function & 0x7F,
                crc=raw[-2] | raw[-1] << 8,
                crc_expected=crc16(raw[:-2]),
            )
            if length > MAX_ADU:  # (a length rule's, its CRC good: _match)
                frame.warnings.append(text("over_adu", length=length, limit=MAX_ADU))
            self._emit(frame, items)
            i += length
        if i:
            self._consume(i)
        return items
