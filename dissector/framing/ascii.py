"""Modbus ASCII framer: `:` + hex pairs (slave, function, data, LRC) + CR LF.

Unlike RTU, ASCII frames delimit themselves: a frame starts at ':' and ends at LF, so no length rule
is needed to cut the stream. The length rules still decide what a frame is: the decoded binary gets
the same request / response / exception classification as an RTU frame (rules.py Awaiting._interpretations, applied to
the RTU frame that would carry the same bytes). A line whose length fits no layout is a frame all the same when
its LRC is good (the ':' and the line end bound it, as a record or a silence bounds an RTU frame whose CRC is
good: bounded.py), with what the decoder says of its bytes; with a bad LRC it is noise.

A candidate that is cut short (a new ':' before the LF, no LF within the longest legal frame, the
end of the capture), that is not made of hex pairs or whose layout fits nothing with a bad LRC becomes a Noise item
of its own, with the reason; the answer awaited cut by the end of the capture says so as in RTU ("the
capture ends inside the response (10 of 17 bytes)", bytes on the wire), which pairing shows on its
request. A line that lost its CR (text files lose them) is a frame with a warning, and so is one that
lost its LF (CR, then the next ':' or the end of the capture: the CR ends the line, a cut frame ends in a hex
digit), one with CRs doubled (a tty's LF to CR LF), one whose LF
is another byte (CR, that byte, then ':' or the end: the frame keeps it, the warning names it), and one
from a reserved address (248..255, the decoder's warning); bytes between frames are noise too. A bad LRC on a frame whose layout fits gives a Frame with crc != crc_expected, shown as
damaged. The answer does not depend on how the stream is split into chunks.

FC8 sub-function 3 (Change ASCII Input Delimiter) replaces the LF of a slave's lines with the character its
request's data carries (the high byte, [diagnostic_data] `character`): once the slave's answer echoes the
change (the echo may end with CR and it already), CR and that character end a line too (the frame keeps both
bytes), for any slave, as LF still does
(no byte says which slave a line is for before it is read). A change back to LF, or to CR or ':' (which
cannot end a line after a CR), drops the slave's character. Once read, a line is checked against its slave's
(_check_end): a request to the slave that set a character ends with it, a warning says so otherwise.
"""
from __future__ import annotations

from dissector.protocol.crc import crc_bytes, lrc
from dissector.framing.rtu import MAX_ADU, MAX_COUNTED, NEED, Awaiting, Scan
from dissector.model import Frame, Item, Kind, Noise
from dissector.framing.stream import StreamFramer

from dissector.protocol.ascii import _HEX_DIGITS, COLON, CR, LF, MAX_ASCII, MIN_BINARY
from dissector.protocol.rules import text
from dissector.protocol.spec import SPEC
from dissector.framing.timing import DEFAULT_BAUD

# FC8 sub-functions whose request data word is a character then 00: the delimiter they set (sub-function 3).
DELIMITER_SUBFUNCTIONS = frozenset(sub for sub, rule in SPEC.diagnostic_data.items() if rule.character)


class AsciiFramer(Awaiting, StreamFramer):
    """Push parser with RtuFramer's interface: feed chunks, collect items in stream order."""

    mode = "ascii"

    def __init__(self, baud: int = DEFAULT_BAUD) -> None:
        super().__init__(baud)
        self._delimiters: dict[int, int] = {}  # slave -> the character 08/03 set in place of LF
        self._line_ends = b""  # those characters: each ends a line after a CR

    def _part_fields(self, data: bytes) -> tuple[int | None, int | None]:
        """What the characters of a frame cut short tell (StreamFramer._cut_part): after its colon, the slave's
        two hex digits, then the function's; None where not captured."""
        fields: list[int | None] = [None, None]
        for index, at in enumerate((1, 3)):
            digits = data[at : at + 2]
            if data[:1] != b":" or len(digits) < 2 or not all(digit in _HEX_DIGITS for digit in digits):
                break
            fields[index] = int(digits, 16)
        return fields[0], fields[1]

    def _run(self, final: bool) -> list[Item]:
        buf = self._buf
        n = len(buf)
        i = 0
        items: list[Item] = []
        while i < n:
            if buf[i] != COLON:
                colon = buf.find(b":", i)
                end = n if colon < 0 else colon
                self._add_noise(i, end, text("outside_ascii"), items)
                i = end
                continue
            limit = min(n, i + MAX_ASCII)
            lf = buf.find(b"\n", i + 1, limit)
            if self._line_ends:
                lf = self._changed_end(buf, i, limit, lf)
            colon = buf.find(b":", i + 1, limit)
            if colon >= 0 and (lf < 0 or colon < lf):
                # (the LF lost, or another byte in its place: the CR ended the line)
                if buf[colon - 1] == CR or (colon - 2 > i and buf[colon - 2] == CR):
                    self._candidate(bytes(buf[i:colon]), i, items)
                else:
                    self._reject(bytes(buf[i:colon]), i, text("cut_by_colon"), items)
                i = colon
            elif lf >= 0:
                end = lf + 1
                if buf[lf - 1] != CR:  # (no CR before the LF: a CR right after it is the line end reversed, LF CR)
                    if end == n and not final:
                        break  # (the next byte tells)
                    end += end < n and buf[end] == CR
                self._candidate(bytes(buf[i:end]), i, items)
                i = end
            elif n - i >= MAX_ASCII and (end := self._long_line(buf, i, n, final)):
                if end == NEED:
                    break
                self._candidate(bytes(buf[i:end]), i, items)
                i = end
            elif n - i >= MAX_ASCII:
                self._reject(bytes(buf[i : i + MAX_ASCII]), i, text("no_line_end", limit=MAX_ASCII), items)
                i += MAX_ASCII
            elif final and n - i > 2 and CR in (buf[n - 2], buf[n - 1]):
                # (the line's CR, its LF lost or another byte in its place: a line, as before a ':')
                self._candidate(bytes(buf[i:n]), i, items, at_end=True)
                i = n
            elif final:
                self._reject(bytes(buf[i:n]), i, self._cut_answer(buf, i, n) or text("cut_by_end"), items)
                i = n
            else:
                break  # wait for the rest of the frame
        if i:
            self._consume(i)
        return items

    def _long_line(self, buf: bytearray, i: int, n: int, final: bool) -> int:
        """Where a line from i longer than MAX_ASCII ends when its header gives its length (an RTU frame's over
        MAX_ADU: rules.MAX_COUNTED) and it is that frame: hex pairs, CR LF there, its LRC good; 0: not one (the
        bytes are noise as before), NEED: its bytes have not all come. A header only fixes where to look: the
        bytes weighed stay bounded."""
        head = bytes(buf[i + 1 : i + MAX_ASCII])  # (the hex pairs of MAX_ADU bytes: they have come, no LF among them)
        if any(byte not in _HEX_DIGITS for byte in head):
            return 0
        binary = bytes.fromhex(head.decode())
        for _kind, rule in self._interpretations(binary, 0):
            length = rule(binary, 0, len(binary))
            if type(length) is Scan or not MAX_ADU < length <= MAX_COUNTED:
                continue
            end = 1 + 2 * (length - 1) + 2  # (':', the ADU's hex pairs and the LRC's, CR LF)
            digits = bytes(buf[i + 1 : min(n, i + end - 2)])
            if any(byte not in _HEX_DIGITS for byte in digits[len(head) :]):
                return 0
            if n - i < end:
                return 0 if final else NEED
            binary = bytes.fromhex(digits.decode())
            return i + end if buf[i + end - 2 : i + end] == b"\r\n" and lrc(binary[:-1]) == binary[-1] else 0
        return 0

    def _changed_end(self, buf: bytearray, i: int, limit: int, lf: int) -> int:
        """Where the line from i ends: at a delimiter 08/03 set, after a CR, before the LF at `lf` (-1: none)
        and `limit` (its position); else at `lf`."""
        stop = limit if lf < 0 else lf
        cr = buf.find(b"\r", i + 1, stop)
        while 0 <= cr < stop - 1:
            if buf[cr + 1] in self._line_ends:
                return cr + 1
            cr = buf.find(b"\r", cr + 1, stop)
        return lf

    def _changed(self, binary: bytes) -> None:
        """A normal answer to 08/03 (Change ASCII Input Delimiter) echoes the change: its slave's lines may end
        with CR and that character from now on. The echo is the server's word that it took the change, so the
        character is the data's high byte (the spec's place) whatever the low byte: pymodbus's client sends
        0021, its server takes 00 and ends its echo and every later line with CR 00."""
        if binary[1] != 8 or len(binary) != 7 or binary[2] << 8 | binary[3] not in DELIMITER_SUBFUNCTIONS:
            return
        character = binary[4]
        if character in (LF, CR, COLON):
            self._delimiters.pop(binary[0], None)
        else:
            self._delimiters[binary[0]] = character
        self._line_ends = bytes(sorted(set(self._delimiters.values())))

    def _candidate(self, raw: bytes, i: int, items: list[Item], at_end: bool = False) -> None:
        """A ':' ... LF run (or ':' ... CR, its LF lost, or ':' ... CR and the byte in the LF's place): a Frame
        when it is one, a Noise item saying why not otherwise. `at_end`: the run ends the capture."""
        reversed_end = raw[-2:] == b"\n\r"  # (LF CR: _run)
        lost_lf = raw[-1] == CR and not reversed_end
        body = raw[1:-2] if reversed_end else raw[1:] if lost_lf else raw[1:-1]
        # Text files lose their CRs (a copy through a Unix tool, a log): LF alone still ends the frame; LF then CR
        # (reversed) too, the frame keeping the CR. A tty that turns LF into CR LF doubles the CR: the frame keeps
        # them all, with a warning.
        digits = body.rstrip(b"\r")
        crs = len(body) - len(digits)
        lost_cr = crs == 0 and not reversed_end
        if len(digits) % 2 or any(byte not in _HEX_DIGITS for byte in digits):
            self._reject(raw, i, text("not_hex_pairs"), items)
            return
        binary = bytes.fromhex(digits.decode("ascii"))
        if len(binary) < MIN_BINARY:
            self._reject(raw, i, text("ascii_too_short"), items)
            return
        slave, function = binary[0], binary[1]
        received, expected = binary[-1], lrc(binary[:-1])
        kind = self._classify(binary[:-1])
        if kind is None and received != expected:
            check = text("lrc_wrong", received=received, expected=expected)
            self._reject(raw, i, text("no_layout", function=function, check=check), items)
            return
        if kind is None:
            # The ':' and the line end bound it and its LRC is good: a frame, as an RTU run with a good CRC between
            # two bounds is (bounded.py: pymodbus's 118-byte answer to 08/15); the decoder says what its bytes lack.
            kind = self._bounded_kind(binary, 0)
        offset = self._base + i
        frame = Frame(
            offset=offset,
            raw=raw,
            time=self._time_at(offset),
            kind=kind,
            slave=slave,
            function=function & 0x7F,
            crc=received,
            crc_expected=expected,
            mode="ascii",
        )
        if len(raw) > MAX_ASCII:  # (_long_line's)
            frame.warnings.append(text("over_ascii", length=len(raw), limit=MAX_ASCII))
        before = self._delimiters.get(slave)
        if kind is Kind.RESPONSE and received == expected:
            self._changed(binary)
        if lost_lf:
            frame.warnings.append(text("cr_at_end" if at_end else "cr_without_lf"))
        elif lost_cr:
            frame.warnings.append(text("lf_without_cr"))
        elif reversed_end:
            frame.warnings.append(text("lf_then_cr"))
        else:
            self._check_end(frame, raw[-1], before)
        if crs > 1:
            frame.warnings.append(text("extra_cr", count=crs))
        if digits != digits.upper():
            frame.warnings.append(text("lower_case_hex"))
        self._emit(frame, items)

    def _check_end(self, frame: Frame, last: int, before: int | None) -> None:
        """Warn a line ended by CR and `last` that its slave does not take (Application Protocol 6.8.1, 08/03:
        the character replaces LF at the end of the messages the slave takes in). A request to a slave that
        set one ends with it; a broadcast with LF or any slave's (each listener takes its own); an answer with
        LF or its slave's, before (`before`) or after this echo (the spec names the slave's input only: its
        answers may keep LF)."""
        slave = frame.slave
        delimiter = self._delimiters.get(slave)
        if frame.kind is Kind.REQUEST and delimiter is not None:
            if last != delimiter:
                frame.warnings.append(text("delimiter_expected", byte=last, slave=slave, delimiter=delimiter))
            return
        taken = self._line_ends if slave == 0 else (before, delimiter)
        if last != LF and last not in taken:
            frame.warnings.append(text("cr_then_byte", byte=last))

    def _cut_answer(self, buf: bytearray, i: int, n: int) -> str | None:
        """At the end of the input: do bytes i..n (':' and hex digits) begin the answer awaited, cut by the
        end of the capture (rtu.py _cut_answer)? The reason, or None."""
        digits = bytes(buf[i + 1 : n])
        pairs = len(digits) // 2
        if pairs < 2 or any(byte not in _HEX_DIGITS for byte in digits):
            return None
        binary = bytes.fromhex(digits[: 2 * pairs].decode("ascii"))
        if not self._awaited(binary, 0):
            return None
        # (the answer's reading, unless it is not as long as the request implies: then the next, the next request)
        for kind, rule in self._interpretations(binary, 0):
            length = rule(binary, 0, pairs)  # (the RTU frame's, its 2-byte CRC an LRC here)
            longest = MAX_COUNTED  # (a length rule's reach, over MAX_ADU too: _long_line takes such a line whole)
            if type(length) is Scan:
                length, longest = length.declared if length.declared > 0 else NEED, MAX_ADU
            if not self._not_the_answer(kind, length):
                break
        else:
            return None
        characters = 1 + 2 * (length - 1) + 2  # ':', the hex pairs of the ADU and the LRC, CR LF
        if length != NEED and not (n - i < characters and length <= longest):
            return None
        return self._cut_reason(kind, f"{n - i} of {characters} bytes" if length != NEED else f"{n - i} bytes of it")

    def _classify(self, adu: bytes) -> Kind | None:
        """The kind an RTU frame with the same bytes would have, by the framer's length rules."""
        equivalent = adu + crc_bytes(adu)
        length = len(equivalent)
        for kind, rule in self._interpretations(equivalent, 0):
            found = rule(equivalent, 0, length)
            # A layout without a length rule fits any length from its minimum: the ':' and CR LF
            # already delimit the frame.
            if found == length or (type(found) is Scan and length >= found):
                return kind
        return None

    def _reject(self, raw: bytes, i: int, reason: str, items: list[Item]) -> None:
        self._flush_noise(items)
        offset = self._base + i
        items.append(Noise(offset=offset, raw=raw, time=self._time_at(offset), reason=reason,
                           tail=self._tail_at(offset + len(raw), offset)))
