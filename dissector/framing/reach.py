"""Where records that are frames of their own stop the RTU framer (rtu.RtuFramer asks): a record end where a
layout checks out is a frame's end the source gives (_ends_record), and a CRC scan, or a reading that waits for
bytes, does not reach across such a record (_framed_reach, _crosses_framed_record). Answers are kept per record
end while the stream's state and end stay, or while more bytes cannot change them (lua/src/rtu.lua
ends_record's `holds`): one-byte records asked every record end ahead again for each byte (100 KB of
`2b 0e` a record a byte took 70 s).
"""
from __future__ import annotations

from bisect import bisect_left
from heapq import heappop, heappush

from dissector.framing.offsets import EndAnswers
from dissector.framing.rules import MAX_ADU, MAX_COUNTED, MIN_ADU, NEED, NONE, Scan, _crc_ok

SETTLED = 1 << 62  # (a buffer length no stream reaches: no more bytes change the answer)


class RecordEnds:
    """RtuFramer's weighing of record ends (with its own methods and state: _interpretations, _boundaries,
    _boundary_at, _base, _expect, _echo, _ends_memo: StreamFramer's)."""

    def _ends_record(self, buf: bytearray, i: int, n: int) -> bool:
        """Does a layout at i check out and end where its record does (a code without a length rule: its CRC
        checks at the record's end)? The source says a frame ends there: a glitch-byte reading of buf[i] before
        a longer frame crossing that end is not waited for, which held every later record in a single pass."""
        return self._record_end(buf, i, n)[0]

    def _record_end(self, buf: bytearray, i: int, n: int) -> tuple[bool, int]:
        """_ends_record's answer, and the buffer length up to which more bytes cannot change it (exclusive; a
        large number: none can; lua/src/rtu.lua ends_record's `holds`, math.huge there). A reading that needs
        more bytes holds until they come, one that ends past n until n reaches its end, one ending at n until n
        passes it (a silence may still make a record end there); an FC43 object walk that stops short of the
        bytes until the byte it needs comes; a scan that finds no record end before n, or an echo awaited that
        has not all come, only at n."""
        echo = self._echo
        until = SETTLED
        if echo and self._expect == (buf[i], buf[i + 1]) and i + 1 + len(echo) >= n:
            until = n + 1
        for _kind, rule in self._interpretations(buf, i):
            length = rule(buf, i, n)
            longest = MAX_COUNTED  # (a length rule's; a scan's: MAX_ADU)
            if type(length) is Scan:
                longest = MAX_ADU
                walk = length.declared  # (NONE but for an FC43 object walk: its length, NEED short of the bytes)
                if walk == NEED:
                    until = min(until, i + length.wanted + 1)
                elif i + walk > n:
                    until = min(until, i + walk)
                end = self._boundaries.first_after(self._base + i, self._base + n)
                if end is None:
                    until = min(until, n + 1)
                length = end - self._base - i if end is not None and end - self._base - i >= length else NONE
            elif length == NEED:
                until = min(until, n + 1)
            if MIN_ADU <= length <= longest:
                if i + length >= n:
                    until = min(until, i + length if i + length > n else n + 1)
                if i + length <= n and self._boundary_at(i + length) and _crc_ok(buf, i, length):
                    return True, until
        return False, until

    def _crosses_framed_record(self, buf: bytearray, i: int, length: int, n: int) -> bool:
        """Would a reading at i of `length` bytes (NEED: more than there are) swallow a record (or the bytes after
        a silence) that is a frame of its own, the first after i (_framed_reach) starting inside it? Then it is
        none, whether its bytes have come or not: waiting for them (a long answer read from noise, 'ff 01 b0';
        an FC23 request's byte count) held every later record in one pass, and a damaged reading hid the frame."""
        return self._framed_reach(buf, i, n) < (n if length == NEED else min(n, i + length))

    def _framed_reach(self, buf: bytearray, i: int, n: int) -> int:
        """Where a CRC scan from i stops: the first record (or bytes after a silence) after i that is a frame of
        its own (_ends_record), else n. Across it a scan read noise and that frame as one frame (its CRC
        matching by chance) and waited for MAX_ADU bytes, holding later records in one pass."""
        base, ends = self._base, self._ends_memo
        last, state = base + n, (self._expect, self._echo)
        low, high = base + i + 1, base + min(n - MIN_ADU + 1, i + MAX_ADU)  # (the record ends weighed: low..high-1)
        if last < ends.last or len(ends.answers) > 4 * MAX_ADU and not ends.prune(base, 4 * MAX_ADU):
            ends.reset(state)
        elif ends.state != state:
            # (the answer awaited and its echo weigh the record ends that start as it does alone: _awaited)
            for key in {ends.state[0], state[0]} - {None}:
                for offset in ends.starts.pop(key, ()):
                    if ends.answers.pop(offset, None) is not None and offset > base:
                        self._answer_end(ends, buf, offset, n)
            ends.state = state
        ends.last = last
        expiry, answers = ends.expiry, ends.answers
        while expiry and expiry[0][0] <= last:  # (answers the bytes come since may change: asked again)
            until, offset = heappop(expiry)
            if answers.get(offset, (False, -1, None))[1] == until:
                if offset > base:
                    self._answer_end(ends, buf, offset, n)
                else:  # (bytes framed since: never weighed again)
                    del answers[offset]
        if high > low:
            if ends.low <= low <= ends.high or ends.low <= high <= ends.high:
                missing = [(low, ends.low), (ends.high, high)]
                ends.low, ends.high = min(low, ends.low), max(high, ends.high)
            else:
                missing = [(low, high)]
                ends.low, ends.high = low, high
            for start, stop in missing:
                for offset in self._boundaries.within(start, stop):
                    if offset not in answers:
                        self._answer_end(ends, buf, offset, n)
        trues = ends.trues
        at = bisect_left(trues, low)
        return trues[at] - base if at < len(trues) and trues[at] < high else n

    def _answer_end(self, ends: EndAnswers, buf: bytearray, offset: int, n: int) -> None:
        """A record end's answer, kept with the stream end up to which it holds."""
        base = self._base
        answer, until = self._record_end(buf, offset - base, n)
        key = (buf[offset - base], buf[offset - base + 1] & 0x7F)
        if ends.answers.get(offset, (False, -1, None))[2] != key:
            ends.starts.setdefault(key, []).append(offset)
        ends.answers[offset] = (answer, base + until, key)
        trues = ends.trues
        at = bisect_left(trues, offset)
        there = at < len(trues) and trues[at] == offset
        if answer and not there:
            trues.insert(at, offset)
        elif there and not answer:
            del trues[at]
        if until < SETTLED:
            heappush(ends.expiry, (base + until, offset))

