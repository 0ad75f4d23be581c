"""Where records that are frames of their own stop the RTU framer (rtu.RtuFramer asks): a record end where a
layout checks out is a frame's end the source gives (_ends_record), and a CRC scan, or a reading that waits for
bytes, does not reach across such a record (_framed_reach, _crosses_framed_record). Answers are kept per record
end while the stream's state and end stay, or while more bytes cannot change them (lua/src/rtu.lua
ends_record's `settled`): one-byte records asked every record end ahead again for each byte (100 KB of
`2b 0e` a record a byte took 70 s).
"""
from __future__ import annotations

from dissector.framing.rules import MAX_ADU, MIN_ADU, NEED, NONE, Scan, _crc_ok

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
        large number: none can; lua/src/rtu.lua ends_record's `settled` is this past n). A reading that needs
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
            if type(length) is Scan:
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
            if MIN_ADU <= length <= MAX_ADU:
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
        base, memo = self._base, self._ends_memo
        last, expect, echo = base + n, self._expect, self._echo  # (what the answer depends on, besides the bytes)
        if len(memo) > 4 * MAX_ADU:
            memo.clear()
        # (in ascending order: the first that is a frame of its own is the reach; an answer is asked again when the
        # stream grew past what it holds for: one-byte records asked every record end ahead again for each byte)
        for offset in self._boundaries.within(base + i + 1, base + min(n - MIN_ADU + 1, i + MAX_ADU)):
            known = memo.get(offset)
            if known is None or known[1] != expect or known[2] != echo or not known[0] <= last < known[4]:
                answer, until = self._record_end(buf, offset - base, n)
                known = memo[offset] = (last, expect, echo, answer, base + until)
            if known[3]:
                return offset - base
        return n
