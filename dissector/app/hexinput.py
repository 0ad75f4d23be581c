"""`--hex`: frames typed from a manual, one frame per argument.

Because the user says where each frame ends, a typed RTU frame that fails its CRC is most likely a
typo (or a frame written without its CRC, as manuals print them): rather than calling it noise, the
frame is decoded and the check is spelled out:

    0C 03 20 D0 00 03 0E EE   -> decoded; "CRC bad: received 0xEE0E, expected 0xEF0E (on the wire
                                 0E EE typed, 0E EF expected)" and the summary's CRC BAD column
    0C 03 20 D0 00 03         -> decoded with the CRC computed; "no CRC typed: append 0E EF"
    :02062329000A             -> decoded with the LRC computed; "no LRC typed: append A2"

A frame is only taken that way when the framer, shown the bytes with the right CRC, finds exactly
that one frame in them; anything else is fed as typed (and shows up as noise). A frame whose length its
data sets (FC8 00, a user-defined code) is one frame both ways: its last two bytes are taken for data, the
CRC left untyped, unless they are the CRC nearly right (a digit off, high byte first). An argument whose bytes
already split into frames with good CRCs (a request and its answer pasted as one) is fed as typed.
A packet dump pasted whole (tshark -x, Wireshark's Copy > Bytes as Hex + ASCII Dump) is its packets, and lines
of a Modbus Poll / Modbus Slave traffic log (`Tx:000001-01 03 ...`) its lines, a frame each, as standard input
reads them (sources/packetdump.py, sources/traffic.py).
"""
from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass

from dissector.errors import UsageError
from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.framing.rules import spans_a_frame
from dissector.model import Chunk, Frame, Item
from dissector.protocol.crc import crc16, crc_bytes, lrc
from dissector.sources.common import Input, SourceError, WarningLog
from dissector.sources.hexdump import HexLineError, parse_line
from dissector.sources.notation import Notation, NotationError
from dissector.sources.packetdump import looks_like_packet_dump, read_packet_dump
from dissector.sources.traffic import looks_like_traffic, parse_traffic_line


@dataclass(frozen=True, slots=True)
class Repair:
    typed: bytes | None  # the bytes as typed, when they differ from the frame fed only by the CRC
    note: str


# How manuals, logs and the README print an ASCII frame's end: the C escapes `\r\n` (typed in a shell's
# quotes they stay a backslash and a letter), the words CR LF, <CR><LF>, [CR][LF]. None holds a hex digit
# pair, so taking them off never eats a byte.
_ASCII_ENDS = ("\\r", "\\n", "<cr>", "<lf>", "[cr]", "[lf]", "cr", "lf")
_HEX_DIGITS = frozenset("0123456789ABCDEFabcdef")


def _without_end(frame: str) -> str:
    """A typed frame without the CR LF written after it (_ASCII_ENDS, any case, any spacing)."""
    frame = frame.rstrip()
    while True:
        end = next((end for end in _ASCII_ENDS if frame.lower().endswith(end)), None)
        if end is None:
            return frame
        frame = frame[: -len(end)].rstrip()


def _without_typed_end(groups: list[str]) -> list[str]:
    """The groups without a CR LF typed as the hex of its bytes (`... A2 0D 0A`, as manuals print an
    ASCII frame's bytes), when that is what the LRC says: the digits before it end with a good LRC and
    the digits with it do not."""
    if len(groups) < 3 or [group.upper() for group in groups[-2:]] != ["0D", "0A"]:
        return groups

    def lrc_good(digits: str) -> bool:
        data = bytes.fromhex(digits)
        return len(data) >= 2 and lrc(data[:-1]) == data[-1]

    return groups[:-2] if lrc_good("".join(groups[:-2])) and not lrc_good("".join(groups)) else groups


def _shown(text: str) -> str:
    """`text` in quotes as typed (a backslash stays one), escaped only when it holds what a terminal
    would not show as itself."""
    return f"'{text}'" if text.isprintable() else repr(text)


def ascii_frames(text: str, where: str = "--hex") -> bytes:
    """The bytes of Modbus ASCII frames typed as printed: `:02062329000AA2`, `:0206 2329 000A A2`, with or
    without their end (`\\r\\n`, `CR LF`: _ASCII_ENDS), several in a row (`:...A2\\r\\n:...`). Each frame
    is `:`, its hex digits as typed (spaces between whole bytes dropped, as in a hex dump) and CR LF.
    Anything else is refused (UsageError): a typed frame that became noise would say nothing of why."""
    typed = text.strip()
    out = bytearray()
    for frame in typed.split(":")[1:]:
        groups = _without_end(frame).split()
        for group in groups:
            bad = next((char for char in group if char not in _HEX_DIGITS), None)
            if bad is not None:
                raise UsageError(
                    f"{where}: {_shown(bad)} in {_shown(typed)} is not a hex digit (an ASCII frame is ':', hex "
                    "digits and CR LF, which may be typed as \\r\\n or CR LF, or left out)"
                )
            if len(group) % 2:
                raise UsageError(f"{where}: '{group}' is an odd number of hex digits (each group is whole bytes)")
        if not groups:
            raise UsageError(f"{where}: no hex digits after a ':' in {_shown(typed)}")
        groups = _without_typed_end(groups)
        out += b":" + "".join(groups).encode("ascii") + b"\r\n"
    return bytes(out)


def hex_chunk(text: str, notation: Notation | None = None, where: str = "--hex") -> Chunk:
    """Bytes typed from a manual or pasted from a log: hex pairs (`0C 03 20 D0 ...`, `0x0C,0x03`,
    `0C:03:20:D0`), a decimal list (`12, 3, 32, 208`; notation.py says when a list is decimal), or a
    Modbus ASCII frame as printed (`:02062329000AA2`, ascii_frames). Each line is read as a hex dump file's
    (sources/hexdump.py parse_line: NModbus's `TX: 1, 3, 0, 22, ...` too; before, --hex refused what the file
    reader took). One argument is one frame: a boundary follows. `notation` carries what earlier arguments
    showed."""
    stripped = text.strip()
    if stripped.startswith(":"):
        return Chunk(ascii_frames(text, where), None, True)
    known = notation if notation is not None else Notation()
    lines = text.splitlines() or [text]
    data = bytearray()
    try:  # (each line as a hex dump file's: a TX:/RX: label, a time stamp (untimed here) or a # note passed over)
        for number, line in enumerate(lines, start=1):
            parsed = parse_line(line, known, where if len(lines) == 1 else f"{where} line {number}")
            data += parsed[1] if parsed is not None else b""
    except (NotationError, HexLineError) as error:
        raise UsageError(f"{where}: {error}") from None
    if not data:
        raise UsageError(f"{where}: no bytes in {text!r}")
    return Chunk(bytes(data), None, True)


def typed_chunks(text: str, notation: Notation | None = None, where: str = "--hex") -> list[Chunk]:
    """The chunks of one --hex argument: a packet dump's packets (its character column shows its bytes, so
    the offsets are no data: `0000  01 03 ...  ........`) or a traffic log's lines (`Tx:000001-01 03 ...`: the
    counter is no data), one frame each, untimed as any typed frame; else hex_chunk's one."""
    ended = text if text.endswith("\n") else text + "\n"
    if looks_like_traffic(ended, complete=True):
        lines = [parse_traffic_line(line) for line in text.splitlines()]
        return [Chunk(line[1], None, True) for line in lines if line is not None]
    if not looks_like_packet_dump(ended, complete=True):
        return [hex_chunk(text, notation, where)]
    stream = Input(io.BytesIO(text.encode("utf-8")), where)
    try:
        return [Chunk(chunk.data, None, True) for chunk in read_packet_dump(stream, WarningLog(), len(text) + 1)]
    except SourceError as error:  # a line missing or doubled: bytes the user did not paste
        raise UsageError(str(error)) from None


def _one_frame(data: bytes, ascii: bool = False) -> bool:
    """Does the framer find exactly one frame, with a good check, covering all of `data`, of a length a layout
    gives (an RTU record with a good CRC is a frame whatever its length, framing/bounded.py: a typo's mending
    asks for the table's shapes, rules.spans_a_frame)?"""
    framer = AsciiFramer() if ascii else RtuFramer()
    items = framer.feed(Chunk(data, None, True)) + framer.finish()
    whole = len(items) == 1 and isinstance(items[0], Frame) and items[0].crc_ok and items[0].length == len(data)
    if whole and ascii:  # (a line with a good LRC is a frame whatever its length: the RTU frame of its bytes' shape)
        adu = bytes.fromhex(data[1:].rstrip(b"\r\n").decode("ascii"))[:-1]
        data = adu + crc_bytes(adu)
    return whole and spans_a_frame(data)


def _good_frames(data: bytes) -> bool:
    """Do the bytes as typed already split into several frames, each with a good CRC, covering all of
    `data`? Then the argument holds several frames (an answer pasted after its request, a log line) and
    nothing was mistyped: a variable-length frame (FC8, a user-defined code) would otherwise be read as
    one long frame whose last two bytes are its CRC."""
    framer = RtuFramer()
    items = framer.feed(Chunk(data, None, True)) + framer.finish()
    return (
        len(items) > 1
        and all(isinstance(item, Frame) and item.crc_ok for item in items)
        and sum(item.length for item in items) == len(data)
    )


def _unended(data: bytes, awaiting: RtuFramer) -> bool:
    """Are `data` with their CRC appended one frame too (a length its data sets: FC8 00, a user-defined code)?
    Then their last two bytes are data as well as a CRC, and typed without a CRC as manuals print a frame is
    the likelier (as an ASCII frame typed without its LRC is read)."""
    whole = data + crc_bytes(data)
    return _one_frame(whole) and awaiting.cut_answer(whole) is None


def _near(typed: int, expected: int) -> bool:
    """A CRC typed nearly right: one hex digit off, or its bytes swapped (written high byte first)."""
    digits_off = sum((typed ^ expected) >> shift & 0xF != 0 for shift in (0, 4, 8, 12))
    return digits_off == 1 or typed == (expected >> 8 | (expected & 0xFF) << 8)


def _wire(crc: int) -> str:
    return f"{crc & 0xFF:02X} {crc >> 8:02X}"


class HexInput:
    """The chunks of the --hex arguments, and the notes their frames get once decoded."""

    def __init__(self, texts: Sequence[str], mode: str | None, notation: str | None = None) -> None:
        """`notation`: "hex" or "decimal" when --format says so, else learned from the arguments."""
        known = Notation(notation, fixed=True) if notation is not None else Notation()
        several = len(texts) > 1
        chunks = [
            chunk for number, text in enumerate(texts, start=1)
            for chunk in typed_chunks(text, known, f"--hex argument {number}" if several else "--hex")
        ]
        self.mode = mode or ("ascii" if chunks[0].data[:1] == b":" else "rtu")
        self.repairs: dict[int, Repair] = {}
        self.chunks: list[Chunk] = []
        offset = 0
        awaiting = RtuFramer()  # what the frames typed so far await: a short answer is no typo
        for chunk in chunks:
            if self.mode == "rtu":
                chunk = self._mend(chunk, offset, awaiting)
                awaiting.feed(chunk)
            elif chunk.data[:1] == b":":
                chunk = self._mend_ascii(chunk, offset)
            self.chunks.append(chunk)
            offset += len(chunk.data)

    def _mend(self, chunk: Chunk, offset: int, awaiting: RtuFramer) -> Chunk:
        data = chunk.data
        # An answer shorter than the request calls for is cut (the capture ends inside it), not mistyped;
        # unless it is whole once its CRC is appended.
        cut = awaiting.cut_answer(data) is not None
        if _good_frames(data):
            return chunk
        if len(data) >= 4 and not cut:
            body, typed = data[:-2], data[-2] | data[-1] << 8
            expected = crc16(body)
            if typed == expected:
                return chunk
            fixed = body + expected.to_bytes(2, "little")
            if _one_frame(fixed) and not (_unended(data, awaiting) and not _near(typed, expected)):
                self.repairs[offset] = Repair(
                    data,
                    f"CRC bad: received 0x{typed:04X}, expected 0x{expected:04X} "
                    f"(on the wire {_wire(typed)} typed, {_wire(expected)} expected)",
                )
                return Chunk(fixed, None, True)
        if len(data) >= 2:
            crc = crc16(data)
            whole = data + crc.to_bytes(2, "little")
            if _one_frame(whole) and awaiting.cut_answer(whole) is None:
                self.repairs[offset] = Repair(None, f"no CRC typed: append {_wire(crc)} (CRC 0x{crc:04X})")
                return Chunk(whole, None, True)
        return chunk

    def _mend_ascii(self, chunk: Chunk, offset: int) -> Chunk:
        """An ASCII frame typed without its LRC (a bad LRC the framer shows by itself)."""
        body = chunk.data[1:-2]
        if _one_frame(chunk.data, ascii=True) or len(body) % 2:
            return chunk
        try:
            check = lrc(bytes.fromhex(body.decode("ascii")))
        except ValueError:
            return chunk
        whole = b":" + body + f"{check:02X}".encode() + b"\r\n"
        if not _one_frame(whole, ascii=True):
            return chunk
        self.repairs[offset] = Repair(None, f"no LRC typed: append {check:02X}")
        return Chunk(whole, None, True)

    def fix(self, items: list[Item]) -> list[Item]:
        """Put the typed bytes back in the frames decoded from mended ones, with their note."""
        if self.repairs:
            for item in items:
                repair = self.repairs.get(item.offset) if isinstance(item, Frame) else None
                if repair is None:
                    continue
                if repair.typed is not None:
                    item.raw = repair.typed
                    item.crc = repair.typed[-2] | repair.typed[-1] << 8
                    item.warnings.append(repair.note)
                else:
                    item.notes.append(repair.note)
        return items
