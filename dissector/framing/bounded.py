"""What the line's bounds say to the RTU framer (rtu.RtuFramer._run asks): bytes with a good CRC between two
bounds are a frame, whatever length the protocol table expects of their layout (asked where no layout checks
out: _bounded_run); bytes from a bound that begin a request are a request the end of the capture cuts, the
next poll (_cut_request), where no answer awaited begins (RtuFramer._cut_answer weighs that one); the intact
frames inside bytes, where records that are frames bound them too (_intact_inside, _framed_inside).

A bound is a record's start or end (a pcap record, a hex-dump line, a --hex argument), a silence of t3.5
or more in a timed capture, the end of a frame the framer took, and for a run's end the start of an intact
frame or the end of the input. A run from one to the next is what tshark's mbrtu shows as a frame when a
record holds it: pymodbus's answer to FC8 sub-function 15h (118 bytes where the table's FC8 layout takes 8),
an exception to function 0 (`11 80 01` + CRC). Only the first CRC match from a bound that ends at one is
taken: once in 65,536 runs for random bytes. Bytes after noise are bound by nothing (a raw byte stream
resynchronising): no length is guessed there, each position and length tried would be another 1 in 65,536
chance of inventing a frame.
"""
from __future__ import annotations

from dissector.framing.rules import MAX_ADU, MAX_COUNTED, MAX_SLAVE, MIN_ADU, NEED, NOT_BROADCAST, Scan, _crc_ok
from dissector.model import Frame, Kind
from dissector.protocol.rules import text

# Why bytes are noise (data/modbus.toml [texts]): no frame starts there; too few left for one.
NO_FRAME, TOO_SHORT = text("no_frame"), text("too_short")


class Bounded:
    """What RtuFramer weighs at a bound (with its own methods: _boundary_at, _valid_frame_at...; _framed_end,
    StreamFramer's: where the last frame ends): the intact frames inside bytes, where records that are frames
    bound them too; runs the line bounds; requests the end of the capture cuts."""

    def _intact_inside(self, buf: bytearray, i: int, length: int, n: int, final: bool) -> bool | None:
        """Does a frame with a length rule and a good CRC start inside bytes i..i+length? None when
        bytes still to come may tell: a layout starting inside ends past the bytes buffered (deciding
        before they come made the answer depend on where the input was cut)."""
        undecided = False
        for j in range(i + 1, i + length):
            found = self._valid_frame_at(buf, j, n, final, scan=False)
            if found:
                return True
            undecided = undecided or found is None
        return None if undecided else False

    def _framed_inside(self, buf: bytearray, i: int, length: int, n: int, final: bool) -> bool | None:
        """_intact_inside, where records that are frames (a record that is this one, or the next one a frame:
        _ends_record) say no frame it holds crosses its record's end: one is not waited for (which held every
        later record in the plugin's one pass). A record's end alone does not say it: a USB adapter's reads end
        anywhere (bench/noise_accuracy.py, bursts)."""
        end = i + length
        bounded = self._boundary_at(end) and (
            self._record_starts_at(i) or (n - end >= MIN_ADU and self._ends_record(buf, end, n))
        )
        return self._intact_inside(buf, i, length, end if bounded else n, final or bounded)

    def _bounded_start(self, i: int) -> bool:
        """Does a bound (a record's start or end, a silence, a frame's end) fall at buffer index i?"""
        return self._boundary_at(i) or self._record_starts_at(i) or self._framed_end == self._base + i

    def _bounded_run(self, buf: bytearray, i: int, n: int, final: bool) -> int:
        """The length of the run from i to the next bound when its CRC is good: the first intact frame, record's
        end or silence after i (a run crosses none: a USB read ends anywhere, but a frame across it is no run
        the line bounds), or the end of the input; 0: none, NEED: the bytes that tell have not come yet. One
        candidate a bound: an intact frame inside a run ends it, so a glitch byte before a frame is no run."""
        if not self._bounded_start(i):
            return 0
        end = self._boundaries.first_after(self._base + i, self._base + n)
        # (up to a record's end or silence, the frames inside it only: as if the input ended there)
        stop, last = (end - self._base, True) if end is not None else (n, final)
        for end in range(i + 1, min(stop, i + MAX_ADU) + 1):
            found = self._valid_frame_at(buf, end, stop, last, scan=False)  # (at `stop` itself: True when last)
            if found is None:
                return NEED
            if found:
                return end - i if end - i >= MIN_ADU and _crc_ok(buf, i, end - i) else 0
        return NEED if not last and n - i < MAX_ADU else 0

    def _bounded_frame(self, buf: bytearray, i: int, length: int, n: int) -> Frame:
        """The frame of the bounded run i..i+length, with a warning when its layout takes another length."""
        function = buf[i + 1]
        kind = self._bounded_kind(buf, i)
        raw = bytes(buf[i : i + length])
        offset = self._base + i
        crc = raw[-2] | raw[-1] << 8
        frame = Frame(offset, raw, self._time_at(offset), kind, buf[i], function & 0x7F, crc, crc)
        expected = self._expected_length(buf, i, n, kind)
        if expected and expected != length:
            frame.warnings.append(text("frame_length", length=length, expected=expected))
        return frame

    def _expected_length(self, buf: bytearray, i: int, n: int, kind: Kind) -> int:
        """The length the protocol table's layout of `kind` at i takes (0: none it fixes by these bytes)."""
        for found, rule in self._interpretations(buf, i):
            if found is kind:
                length = rule(buf, i, n)
                return 0 if type(length) is Scan or length < MIN_ADU else length
        return 0

    def _take_bounded(self, buf: bytearray, i: int, n: int, final: bool, items: list) -> int:
        """Emit the frame of a bounded run at i (_bounded_run): its length, 0 (none) or NEED."""
        length = self._bounded_run(buf, i, n, final)
        if length > 0:
            self._emit(self._bounded_frame(buf, i, length, n), items)
        return length

    def _cut_tail(self, buf: bytearray, i: int, n: int) -> str | None:
        """At the end of the input: the reason bytes i..n begin a frame the end of the capture cuts (the answer
        awaited: RtuFramer._cut_answer, else a request from a bound: _cut_request), or None."""
        return self._cut_answer(buf, i, n) or self._cut_request(buf, i, n)

    def _silence_cut(self, buf: bytearray, i: int, n: int) -> tuple[int, str] | None:
        """Do bytes i..s, up to the first silence s after i, begin a frame the silence cuts: the answer awaited or
        a request from a bound, as _cut_tail weighs them at the end of the input (live closes them at the
        silence: StreamFramer.finish(silence=True); a file must say what live says)? (s, the reason), or None.
        A layout with a good CRC across the silence is a frame (the silence inside it a warning: timing.py)."""
        if not self._silences or not (self._expect is not None or self._bounded_start(i)):
            return None
        base = self._base
        first = self._silences.first_after(base + i, base + n - 1)
        if first is None:
            return None
        stop = first - base
        was, self._cut_by_silence = self._cut_by_silence, True
        try:
            reason = self._cut_tail(buf, i, stop)
        finally:
            self._cut_by_silence = was  # (finish_at's, for the bytes after the silence)
        return (stop, reason) if reason is not None and not self._checks_out(buf, i, n) else None

    def _no_frame(self, i: int) -> str:
        """Why the byte at i, where no frame starts, is noise: 'no valid frame', or 'too short for a frame' where a
        silence comes fewer than a frame's minimum bytes after it: live closes the bytes at the silence, too few for
        one (_run's n - i < MIN_ADU at StreamFramer.finish), and a file says what live says. (A noise item's reason is
        the one given for its first byte: where a run starts, or a silence inside it: _add_noise.)"""
        silences = self._silences
        if silences:
            at = self._base + i
            if at + 1 in silences or at + 2 in silences or at + 3 in silences:  # (MIN_ADU: 4)
                return TOO_SHORT
        return NO_FRAME

    def _add_skipped(self, i: int, end: int, items: list) -> None:
        """Bytes i..end, where no frame starts, are noise: the bytes from each silence inside on with their own
        reason (_no_frame), as live closes them there."""
        if self._silences:
            base = self._base
            for at in [offset - base for offset in self._silences.within(base + i + 1, base + end)]:
                self._add_noise(i, at, self._no_frame(i), items)
                i = at
        self._add_noise(i, end, self._no_frame(i), items)

    def _cut_request(self, buf: bytearray, i: int, n: int) -> str | None:
        """At the end of the input, where no answer awaited begins (_cut_answer weighs that one): do bytes i..n,
        from a bound, begin a request whose length the table knows (or whose count has not come), cut by the end
        of the capture (the next poll)? The reason to show them with, or None."""
        if n - i < 2 or self._awaited(buf, i) or not self._bounded_start(i):
            return None
        slave, function = buf[i], buf[i + 1]
        if not (1 <= slave <= MAX_SLAVE or (slave == 0 and function not in NOT_BROADCAST)):
            return None
        for kind, rule in self._interpretations(buf, i):
            if kind is Kind.REQUEST:
                length = rule(buf, i, n)
                break
        else:
            return None
        if type(length) is Scan or (length != NEED and not n - i < length <= MAX_COUNTED):  # (as _cut_answer)
            return None
        if self._checks_out(buf, i, n) or self._intact_inside(buf, i, n - i, n, True):
            return None
        return self._cut_reason(kind, f"{n - i} of {length} bytes" if length != NEED else f"{n - i} bytes of it")

    def _checks_out(self, buf: bytearray, i: int, n: int) -> bool:
        """Does a layout at i whose length the bytes up to n hold check out: an answer nobody asked for, shorter
        than a request (7 bytes of FC3), or cut before its request reading's byte count (9 of FC23)? (Unlike
        _valid_frame_at, a request reading still without its length does not stop the others.)"""
        for _kind, rule in self._interpretations(buf, i):
            length = rule(buf, i, n)
            if type(length) is Scan:
                if self._shortest_crc(buf, i, n, length):
                    return True
            elif MIN_ADU <= length <= n - i and _crc_ok(buf, i, length):
                return True
        return False
