"""Packet hex dumps as `tshark -x`, Wireshark's Copy › Bytes as Hex + ASCII Dump and `vw3-decode -x` write
them (what text2pcap reads back):

         1     0.000000   2 request   Encapsulated Interface Transport ...    a summary line: passed over
    0000  02 2b 0e 01 02 00 00 04 00 0d 54 65 6c 65 6d 65   .+........Teleme
    0010  63 61 6e 69 71 75 65 01 0b 41 54 56 37 31 48 55   canique..ATV71HU
    0030  49 4e 45 20 34 6f 50                              INE 4oP

Each packet starts at offset 0 and is one record (its bytes, then a frame boundary, as a pcap record),
untimed, but where the packet's details before its bytes give its time (`tshark -V -x`, Wireshark's Export
Packet Dissections as plain text: `Epoch Time: 1767225600.010157000 seconds`, 4.2's `Epoch Arrival Time`;
`vw3-decode -V -x`: `Arrival time: 2026-01-01 00:00:00.010157 UTC`), to the nanosecond, as the capture it
was dissected from had it. A line's offset says where its bytes belong in the packet: one that does not go on where the
line before ended is an error (bytes missing or doubled). The character column is ignored. Lines that
do not start with an offset (tshark -P's and vw3-decode -x's summary lines, blank lines) are passed
over, as text2pcap passes them over.

The format is told by its character column, which no one-frame-a-line hex dump has: every dump line of
the sample shows its own bytes there (printable ASCII as itself, any other byte as '.'), and the first
is at offset 0. `0000  0C 03 20 D0` without it stays a hex dump line (bytes 00 00 0C 03 20 D0).
"""
from __future__ import annotations

import calendar
import re
from collections.abc import Iterator
from datetime import datetime

from dissector.model import Chunk, Stamp
from dissector.sources.common import Input, SourceError, WarningLog
from dissector.sources.hexdump import StampedLines, cut_short, ended_lines

# Offset, two or three spaces (tshark -x: two; Wireshark's copy: three), up to 16 bytes one space apart,
# then the character column at least two spaces on (the hex part is padded to 16 bytes' width).
_LINE = re.compile(r"([0-9a-fA-F]{4,8}) {2,3}((?:[0-9a-fA-F]{2} ){0,15}[0-9a-fA-F]{2})(?:( {2,})(.*))? *")
_OFFSET = re.compile(r"[0-9a-fA-F]{4,8} {2}")  # a line that claims to be a dump line
_CUT = re.compile(r"([0-9a-fA-F]{4,8}) {2,3}((?:[0-9a-fA-F]{2} )*)([0-9a-fA-F]?)")
# The frame tree's time of the packet (tshark 4.0 -V: `Epoch Time: S.NNNNNNNNN seconds`; 4.2 on: `Epoch Arrival
# Time`): the seconds since the epoch, in decimals as the dissector wrote them.
_EPOCH = re.compile(r"\s*Epoch (?:Arrival )?Time: (-?\d+)(?:\.(\d{1,9}))? seconds\s*")
# vw3-decode -V's (render/detail_plain.py): the date and time in UTC, then the time column's reading.
_ARRIVAL = re.compile(r"\s*Arrival time: (\d{4})-(\d\d)-(\d\d) (\d\d):(\d\d):(\d\d)(?:\.(\d{1,9}))? UTC(?: \(.*\))?\s*")


def _characters(data: bytes) -> str:
    return "".join(chr(byte) if 32 <= byte < 127 else "." for byte in data)


def _parse(line: str) -> tuple[int, bytes, str | None] | None:
    """(offset, bytes, character column or None) of a dump line; None for any other line."""
    match = _LINE.fullmatch(line.rstrip("\r\n"))
    if match is None:
        return None
    return int(match.group(1), 16), bytes.fromhex(match.group(2)), match.group(4)


def looks_like_packet_dump(text: str, complete: bool) -> bool:
    """The sample's dump lines (a last one without its line end aside) each show their bytes in the character
    column (trailing spaces aside: an editor may strip them), and the first is at offset 0."""
    lines = text.splitlines()
    if not text.endswith(("\n", "\r")) and (not complete or len(lines) > 1):
        lines = lines[:-1]  # (cut by the sample's end, or the input's: a dump copied while written)
    parsed = [_parse(line) for line in lines]
    dumped = [entry for entry in parsed if entry is not None]
    if not dumped or dumped[0][0] != 0:
        return False
    if any(_OFFSET.match(line) and entry is None for line, entry in zip(lines, parsed)):
        return False  # a line with an offset that is no dump line: not this format
    return all(column is not None and column.rstrip() == _characters(data).rstrip()
               for _offset, data, column in dumped)


def _epoch(line: str) -> Stamp | None:
    found = _EPOCH.fullmatch(line)
    if found is None:
        arrival = _ARRIVAL.fullmatch(line)
        if arrival is None:
            return None
        try:
            parts = [int(part) for part in arrival.groups()[:6]]
            datetime(*parts)  # (a day or an hour that does not exist: no time)
            seconds = calendar.timegm((*parts, 0, 0, 0))
        except ValueError:
            return None
        return Stamp(seconds * 1_000_000_000 + int((arrival.group(7) or "").ljust(9, "0")))
    seconds, fraction = int(found.group(1)), found.group(2) or ""
    return Stamp(seconds * 1_000_000_000 + (-1 if seconds < 0 else 1) * int(fraction.ljust(9, "0")))


def read_packet_dump(inp: Input, log: WarningLog, chunk_size: int) -> StampedLines:
    """One chunk per packet, ending with a boundary; a long packet in pieces of about chunk_size bytes; its
    first piece timed where the packet's details said its time."""
    return StampedLines(_packets(inp, log, chunk_size))


def _packets(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    pending = bytearray()  # the packet's bytes not yet given
    position = 0  # the packet's bytes so far
    told: Stamp | None = None  # the time the details before the coming packet gave
    time: Stamp | None = None  # the packet's at hand, until its first piece is given
    for number, line, ended in ended_lines(inp, chunk_size):
        parsed = _parse(line)
        last = False
        if parsed is None and (stamp := _epoch(line)) is not None:
            told = stamp
            continue
        if parsed is None:
            cut = None if ended else _CUT.fullmatch(line.rstrip())
            if cut is not None:  # the input's last line, cut short inside its bytes: its whole bytes
                parsed, last = (int(cut.group(1), 16), bytes.fromhex(cut.group(2)), None), True
                log.warn("truncated input", cut_short(inp.name, number, parsed[1], cut.group(3)))
            elif _OFFSET.match(line):
                raise SourceError(f"{inp.name} line {number}: not a packet dump line: {line.strip()[:60]!r}")
            else:
                continue  # a summary line, a blank one
        offset, data, _column = parsed
        if offset == 0 and position:
            yield Chunk(bytes(pending), time, True)
            pending.clear()
            position = 0
        if offset == 0:
            time, told = told, None
        if offset != position:
            raise SourceError(f"{inp.name} line {number}: offset {offset:#06x} where {position:#06x} was expected "
                              "(bytes missing or repeated)")
        if len(pending) >= chunk_size:
            yield Chunk(bytes(pending), time)
            pending.clear()
            time = None
        pending += data
        position += len(data)
        if last:
            break
    if pending:
        yield Chunk(bytes(pending), time, True)
