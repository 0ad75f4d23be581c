"""What the line's bounds say to the RTU framer (rtu.RtuFramer._run asks): bytes from a bound that begin a
request are a request the end of the capture cuts, the next poll (_cut_request), where no answer awaited
begins (RtuFramer._cut_answer weighs that one); the intact frames inside bytes, where records that are frames
bound them too (_intact_inside, _framed_inside).

A bound is a record's start or end (a pcap record, a hex-dump line, a --hex argument), a silence of t3.5
or more in a timed capture, or the end of a frame the framer took. Bytes after noise are bound by nothing:
that their first two read as a slave and a function is a 1 in 256 chance or so for random bytes.
"""
from __future__ import annotations

from dissector.framing.rules import MAX_ADU, MAX_SLAVE, MIN_ADU, NEED, NOT_BROADCAST, Scan, _crc_ok
from dissector.model import Kind


class Bounded:
    """What RtuFramer weighs at a bound (with its own methods: _boundary_at, _valid_frame_at...; _framed_end,
    StreamFramer's: where the last frame ends): the intact frames inside bytes, where records that are frames
    bound them too; requests the end of the capture cuts."""

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

    def _cut_tail(self, buf: bytearray, i: int, n: int) -> str | None:
        """At the end of the input: the reason bytes i..n begin a frame the end of the capture cuts (the answer
        awaited: RtuFramer._cut_answer, else a request from a bound: _cut_request), or None."""
        return self._cut_answer(buf, i, n) or self._cut_request(buf, i, n)

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
        if type(length) is Scan or (length != NEED and not n - i < length <= MAX_ADU):
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
