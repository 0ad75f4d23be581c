"""What every capture reader shares: the error type, a forward-only input, a warning log and the
link-layer payloads (USER0, RTAC serial) that pcap and pcapng records carry.
"""
from __future__ import annotations

import os
import stat
import struct
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import BinaryIO

from dissector.errors import SourceError
from dissector.model import Chunk, Stamp
from dissector.sources.ethernet import LINK_NAMES, NETWORK_LINKTYPES, PacketTimes, Transport  # (RTU over TCP/UDP)

LINKTYPE_USER0 = 147
LINKTYPE_RTAC_SERIAL = 250
SUPPORTED_LINKTYPES = ("147 (USER0) and 250 (RTAC serial); Modbus RTU over TCP/UDP from 0, 1, 101, 113, 228, 229 "
                       "and 276 (network links)")
# Names for the link types people most often feed us by mistake, for the error message.
LINKTYPE_NAMES = LINK_NAMES  # (the network links' names: sources/ethernet.py states them once)

RTAC_HEADER = struct.Struct(">IIBBH")  # seconds, microseconds, event type, control lines, footer
# Event types from Wireshark's packet-rtacser.c that mean bytes on the line were lost or damaged.
RTAC_TROUBLE_EVENTS = {
    0x05: "capture data lost",
    0x07: "framing error",
    0x08: "parity error",
    0x09: "serial break",
    0x0A: "serial overflow",
}

# The times every output can show and compute with (issue 32): -t ad/ud dates and -V's arrival time
# (Python's calendar holds the years 1..9999; a day inside it for local time zones), --json, the
# report's dates, --parquet's timestamp[us]. A record stamped outside is refused in one line (exit 2):
# the stamp or the if_tsoffset is corrupt, and no time put in its place would be the truth.
EARLIEST_NS = -62_135_510_400 * 1_000_000_000  # 0001-01-02 00:00:00 UTC
LATEST_NS = 253_402_214_400 * 1_000_000_000  # 9999-12-31 00:00:00 UTC, excluded
TIME_RANGE = "0001-01-02..9999-12-30 UTC"


def outside_time_range(ns: int, offset: int = 0) -> str | None:
    """None for a time (integer nanoseconds from 1970) every output can show; else why not, for the
    reader's one-line refusal (`offset`: a pcapng interface's if_tsoffset, named when not 0)."""
    if EARLIEST_NS <= ns < LATEST_NS:
        return None
    added = f" (if_tsoffset {offset} s)" if offset else ""
    return (f"time {ns // 1_000_000_000} s from 1970{added} is outside {TIME_RANGE}, the times every output "
            "can show: a corrupt time stamp?")


def name_text(name: str) -> str:
    """A file name as messages, titles and outputs show it: each byte that is not UTF-8 (Python's
    os and argv give it as a lone surrogate U+DC80..U+DCFF, PEP 383) as \\xNN, the form the tool escapes
    control characters in (protocol/printable.py). Never the raw byte (tshark prints it: 0x9b is a CSI
    to an 8-bit terminal), nor `\\udcff`, which names no character of the name; written out, it raised
    UnicodeEncodeError (--report)."""
    if name.isascii() or not any("\udc80" <= char <= "\udcff" for char in name):
        return name
    return "".join(f"\\x{ord(char) - 0xDC00:02x}" if "\udc80" <= char <= "\udcff" else char for char in name)


MESSAGES_PER_KIND = 5  # warnings of one kind shown before they are only counted


class WarningLog:
    """Warnings for the user, at most MESSAGES_PER_KIND of each kind, the rest counted.

    A damaged capture can repeat one problem on every record; the user needs to know it happens and
    how often, not to read it a million times.
    """

    def __init__(self) -> None:
        self.messages: list[str] = []
        self._counts: dict[str, int] = {}

    def warn(self, kind: str, message: str) -> None:
        count = self._counts.get(kind, 0) + 1
        self._counts[kind] = count
        if count <= MESSAGES_PER_KIND:
            self.messages.append(message)

    def close(self) -> None:
        """Append the counts of what was not shown (call once, at the end of the input)."""
        for kind, count in self._counts.items():
            if count > MESSAGES_PER_KIND:
                self.messages.append(f"... and {count - MESSAGES_PER_KIND} more {kind}")
        self._counts.clear()


class Where(WarningLog):
    """A log's warnings with where they are said first (`file: if_name: record 2`, `file: TCP a - b: record 2: ...`), counted as its own."""

    def __init__(self, log: WarningLog, where: str) -> None:  # (no state of its own: `log` keeps it)
        self._log, self._where = log, where

    def warn(self, kind: str, message: str) -> None:
        self._log.warn(kind, f"{self._where}{message}")


class Input:
    """A forward-only byte stream with a known position; works the same on files and pipes.

    `prefix` holds bytes already read to detect the format, served before the stream's own.
    """

    def __init__(self, stream: BinaryIO, name: str, prefix: bytes = b"") -> None:
        self.stream = stream
        self.name = name
        self.position = 0
        self._prefix = prefix
        # Pipes and terminals get whatever is there (read1) so that a live feed is not held back.
        self._read_some = getattr(stream, "read1", stream.read)

    def read(self, count: int) -> bytes:
        """Exactly `count` bytes, fewer only at the end of the input."""
        if not self._prefix:
            # A buffered stream's read(n) already waits for n bytes or the end, pipes included.
            try:
                data = self.stream.read(count)
            except OSError as error:
                raise SourceError(f"{self.name}: read error: {error.strerror or error}") from None
            self.position += len(data)
            return data
        parts: list[bytes] = []
        wanted = count
        while wanted > 0:
            part = self.read_some(wanted)
            if not part:
                break
            parts.append(part)
            wanted -= len(part)
        return b"".join(parts)

    def unread(self, data: bytes) -> None:
        """Give back `data`, the bytes just read: they are read again next (a reader that looked ahead)."""
        self._prefix = data + self._prefix
        self.position -= len(data)

    def read_some(self, count: int) -> bytes:
        """Up to `count` bytes, as soon as some are available; b"" at the end of the input."""
        if self._prefix:
            part, self._prefix = self._prefix[:count], self._prefix[count:]
        else:
            try:
                part = self._read_some(count)
            except OSError as error:
                raise SourceError(f"{self.name}: read error: {error.strerror or error}") from None
        self.position += len(part)
        return part

    def seek(self, position: int) -> None:
        """Go to byte `position` of a file read from its start (rereadable), what was given back forgotten."""
        self._prefix = b""
        self.stream.seek(position)
        self.position = position

    def skip(self, count: int, piece: int = 65536) -> int:
        """Discard `count` bytes without holding them; returns how many there were."""
        skipped = 0
        while skipped < count:
            part = self.read(min(piece, count - skipped))
            if not part:
                break
            skipped += len(part)
        return skipped


def rereadable(source: Input | str | None) -> bool:
    """Bytes all there, to read again or ahead without waiting: a regular file, by its path (a second open
    gives them again; not stdin `-`, a FIFO or a device) or open as an Input (a compressed file's descriptor
    is the file's own; bytes in memory when seekable), not a live feed (a pipe, a terminal)."""
    if source is None or source == "-":
        return False
    try:
        if isinstance(source, str):
            return stat.S_ISREG(os.stat(source).st_mode)
        return stat.S_ISREG(os.fstat(source.stream.fileno()).st_mode)
    except (AttributeError, OSError, ValueError):  # (no descriptor: bytes in memory)
        seekable = None if isinstance(source, str) else getattr(source.stream, "seekable", None)
        return bool(seekable and seekable())


def linktype_error(name: str, linktype: int, where: str = "") -> SourceError:
    label = LINKTYPE_NAMES.get(linktype, "not a serial line")
    return SourceError(
        f"{name}: {where}linktype {linktype} ({label}) carries no serial bytes; "
        f"supported: {SUPPORTED_LINKTYPES}"
    )


def check_linktype(name: str, linktype: int, where: str = "") -> None:
    if linktype not in (LINKTYPE_USER0, LINKTYPE_RTAC_SERIAL) and linktype not in NETWORK_LINKTYPES:
        raise linktype_error(name, linktype, where)


def rtac_mark(times: PacketTimes | None, time: Stamp) -> int | None:
    """An RTAC record read at its header's `time`, a packet tshark shows (its serial bytes or none: an event) marked
    in `times` (sources/ethernet.py PacketTimes: -t r counts from the capture's first packet, -t d from the one
    before): the time of the packet before it. The header's time, as -t a/e and the response times take it, not the
    record's, tshark's frame time: they agree on a tap's captures; where they differ, a column counting from one
    clock what another output shows by the other would mix them (a record stored late showed a delta its arrival
    time contradicts)."""
    return None if times is None else times.packet(time.ns)


def rtac_header(head: bytes, record: int, log: WarningLog) -> tuple[Stamp | None, int] | None:
    """(time, header length) from an RTAC serial record's start; None when the header is cut.

    The RTAC's own timestamp (u32 seconds, u32 microseconds, big-endian) is when the device saw
    the bytes, which is what response times need; the pcap record time is when it was stored. Its
    microseconds 1 s or more: a corrupt stamp, the bytes decoded untimed with a warning (tshark's
    rtacser shows the field as it is; 4294967295 us read as 4294.97 s put a response 71 minutes
    before its request; the record's time is of another clock), the record a packet at its record's time
    (record_chunks), as tshark counts it. A record shorter than the header is a packet at its record's time too.
    """
    if len(head) < RTAC_HEADER.size:
        log.warn(
            "records shorter than the RTAC header",
            f"record {record}: {len(head)} bytes, shorter than the 12-byte RTAC serial header; "
            "its bytes are noise",
        )
        return None
    seconds, micros, event, _lines, _footer = RTAC_HEADER.unpack_from(head)
    time: Stamp | None = Stamp.from_parts(seconds, micros, 1_000_000)
    if micros >= 1_000_000:
        log.warn("corrupt time stamps", f"record {record}: RTAC microseconds {micros} are not below 1000000: "
                 "a corrupt time stamp? Its bytes are decoded untimed")
        time = None
    trouble = RTAC_TROUBLE_EVENTS.get(event)
    if trouble is not None:
        log.warn("RTAC line events", f"record {record}: the RTAC reports a {trouble} (event {event:#04x})")
    return time, RTAC_HEADER.size


@dataclass(slots=True)
class NotedChunk(Chunk):
    """The last chunk of a pcapng record that carries packet comments (opt_comment, as `editcap -a` or
    Wireshark write them): the record's number and its comments, for -V, --json and -w (sources/trail.py).
    """

    record: int = 0
    comments: tuple[str, ...] = ()


@dataclass(slots=True)
class StoredChunk(Chunk):
    """Bytes decoded untimed though their record has a time: an RTAC record's whose header microseconds are
    corrupt (rtac_header; its record's clock may not be its header's, so no response time is made of it).
    `stored`, its record's time, is tshark's frame time for it: -w writes the record there (sources/trail.py),
    as it writes such a record of no serial byte. Before, at the epoch: tshark showed the copy's packet in 1970."""

    stored: Stamp | None = None


@dataclass(slots=True)
class PartChunk(NotedChunk):
    """The last chunk of a record captured in part (a snapshot length shorter than it: `editcap -s 5`, tshark's
    `[Packet size limited during capture]`): the line's bytes after it were lost, so the framers cut there
    (framing/stream.py StreamFramer.feed): its bytes are one item, the next record's frame from a clean start.
    `captured` and `original` are the record's lengths as its header gives them, as the warning names them."""

    captured: int = 0
    original: int = 0


def record_chunks(
    inp: Input,
    length: int,
    time: float | None,
    linktype: int,
    record: int,
    log: WarningLog,
    chunk_size: int,
    stamped: Callable[[Stamp], None] | None = None,
    original: int = 0,
    transport: Transport | None = None,
) -> Iterator[Chunk]:
    """The serial bytes of one pcap/pcapng record of `length` captured bytes.

    A record longer than chunk_size comes out in several chunks (memory stays bounded whatever the
    file says); only the last one carries boundary=True. When the input ends inside the record,
    the bytes that are there are still delivered, with a warning and no boundary. `stamped` is given an
    RTAC record's own time, once its header is read: a record of the header alone (an RTAC event: a
    break, a control line) yields no chunk, yet says the tap was recording then (recorded_until). A record
    captured in part (`original`, its length on the line, more than `length`) is one PartChunk, all its bytes
    (before, a record longer than a chunk was cut after its last chunk alone, the others framed as whole bytes),
    none too (0 of its 9 bytes: bytes were lost there all the same; before, no chunk and no cut).
    A network link's record (`transport`: sources/ethernet.py) is its TCP/UDP payload when on the RTU ports,
    one chunk (a record is at most MAX_PACKET bytes), else nothing.
    """
    if transport is not None and linktype not in (LINKTYPE_USER0, LINKTYPE_RTAC_SERIAL):
        yield from _payload_chunks(inp, length, time, linktype, record, log, transport)
        return
    if length == 0 and linktype == LINKTYPE_RTAC_SERIAL:  # (no header: warned as any record shorter than it)
        rtac_header(b"", record, log)
    remaining = length
    first = True
    header_size = 0
    stored = time  # the record's time (an RTAC record's own is its header's, read below)
    part = bytearray() if original > length else None  # (at most a record's MAX_PACKET bytes: pcap.py, pcapng.py)
    while remaining > 0:
        wanted = min(remaining, chunk_size)
        piece = inp.read(wanted)
        remaining -= len(piece)
        cut = len(piece) < wanted
        if cut:
            log.warn(
                "truncated input",
                f"record {record} is cut short: {length - remaining} of {length} bytes "
                "(the capture ends inside it); the bytes that are there are decoded",
            )
        if first and linktype == LINKTYPE_RTAC_SERIAL:
            header = rtac_header(piece, record, log)
            if header is None:
                inp.skip(remaining)
                if piece:  # (a frame tshark shows undissected: its bytes are noise, at its record's time)
                    if stamped is not None and stored is not None:
                        stamped(stored)
                    yield Chunk(piece, stored, not cut)
                    return
                break  # (a packet all the same, tshark's frame at its record's time: below)
            stored, (time, size) = time, header
            piece = piece[size:]
            header_size = size  # (a record captured in part says its serial bytes, as the plugin's tvb holds them)
            if stamped is not None and (time or stored) is not None:  # (a corrupt header's: its record's time)
                stamped(time or stored)  # type: ignore[arg-type]
        first = False
        if part is not None:
            part += piece
            if cut and part:  # (the input ends inside it: its bytes as any record's there, no cut)
                yield Chunk(bytes(part), time, False)
        elif piece and time is None and stored is not None and linktype == LINKTYPE_RTAC_SERIAL:
            yield StoredChunk(piece, None, remaining == 0 and not cut, stored)  # type: ignore[arg-type]
        elif piece:
            yield Chunk(piece, time, remaining == 0 and not cut)
        if cut:
            return
    bare = linktype == LINKTYPE_RTAC_SERIAL and not header_size  # (an RTAC record shorter than its header)
    if part is not None and not bare:
        yield PartChunk(bytes(part), time, True, record, (), length - header_size, original - header_size)
    elif length == header_size and linktype in (LINKTYPE_USER0, LINKTYPE_RTAC_SERIAL) or bare:
        # An empty record (an RTAC's event, its header alone, or one shorter than its header): no byte for the
        # framers (they pass it over), but a packet tshark counts, at its record's time when its header tells
        # none, that -w writes again where it stood (sources/trail.py); before, a copy lost it, its packet
        # numbers slid.
        if bare and stamped is not None and stored is not None:
            stamped(stored)
        yield Chunk(b"", time if time is not None else stored, True)


def _payload_chunks(inp: Input, length: int, time: Stamp | None, linktype: int, record: int, log: WarningLog,
                    transport: Transport) -> Iterator[Chunk]:
    """The bus's bytes of a network record (record_chunks): its payload on the RTU ports, one chunk; a
    payload captured in part a PartChunk (the stream's cut: the bytes after it were lost)."""
    if transport.outside(record):
        inp.skip(length)
        return
    offset = inp.position
    data = inp.read(length)
    if len(data) < length:
        log.warn("truncated input", f"record {record} is cut short: {len(data)} of {length} bytes "
                 "(the capture ends inside it); the bytes that are there are decoded")
    known = len(transport.connections)
    found = transport.take(linktype, data, record, offset, time.ns if time is not None else None)
    if known == 1 and len(transport.connections) == 2 and transport.only is None:
        # (a file is read once per connection, each its own bus: sources/interfaces.py; a pipe cannot be)
        log.warn("connections", "packets come from several connections on the RTU ports; their bytes are decoded "
                 "as one stream (vw3-decode FILE decodes each connection as its own bus: save standard input to a file)")
    if found is None:
        return
    if found.declared > len(found.data):
        log.warn("records captured in part",
                 f"record {record}: only {len(found.data)} of its {found.declared} payload bytes were captured")
        yield PartChunk(found.data, time, True, record, (), len(found.data), found.declared)
    else:
        yield Chunk(found.data, time, True)
