"""Classic pcap (libpcap) files: both byte orders, microsecond and nanosecond timestamps, and the
modified pcap of Alexey Kuznetzov's patched libpcap (editcap -F modpcap, magic a1b2cd34).

A record is one read of the serial line (one frame for most sniffers, any run of bytes for others):
it becomes one Chunk with the record's time and boundary=True. Only the link types that carry raw
serial bytes are accepted (common.SUPPORTED_LINKTYPES), and network links whose TCP/UDP payloads on the RTU
ports are the bus's (sources/ethernet.py); anything else is an error, not noise.
"""
from __future__ import annotations

import struct
from collections.abc import Iterator
from dataclasses import replace

from dissector.model import Chunk, Stamp
from dissector.sources.ethernet import NETWORK_LINKTYPES, PacketTimes, RtuPorts, Span, Transport
from dissector.sources.common import (
    Where,
    LINKTYPE_RTAC_SERIAL,
    rtac_mark,
    Input,
    SourceError,
    WarningLog,
    check_linktype,
    record_chunks,
    rereadable,
)

# Magic as the first four bytes of the file -> (struct byte order, timestamp fraction units).
MAGICS: dict[bytes, tuple[str, int]] = {
    bytes.fromhex("d4c3b2a1"): ("<", 1_000_000),
    bytes.fromhex("a1b2c3d4"): (">", 1_000_000),
    bytes.fromhex("4d3cb2a1"): ("<", 1_000_000_000),
    bytes.fromhex("a1b23c4d"): (">", 1_000_000_000),
}
# Modified pcap: microsecond times; each record header has 8 more bytes (ifindex u32, protocol u16,
# pkt_type u8, pad u8), nothing a serial line needs.
MODIFIED_MAGICS: dict[bytes, str] = {bytes.fromhex("34cdb2a1"): "<", bytes.fromhex("a1b2cd34"): ">"}
MODIFIED_EXTRA = 8
# The record header's bytes after the standard 16 in each variant wiretap's libpcap.c tries, in its order:
# with the standard magic pcap, ss990417 (RedHat 6.1's tcpdump: editcap -F rh6_1pcap) and Nokia IPSO
# (-F nokiapcap); with the modified magic ss991029 (-F modpcap) and ss990915 (SuSE 6.3's: -F suse6_3pcap).
STANDARD_VARIANTS = (0, 8, 4)
MODIFIED_VARIANTS = (MODIFIED_EXTRA, 12)
MAX_PACKET = 262_144  # wiretap's WTAP_MAX_PACKET_SIZE: a longer record says the variant is wrong
FILE_HEADER_SIZE = 24
RECORD_HEADER_SIZE = 16


def is_pcap(head: bytes) -> bool:
    return head[:4] in MAGICS or head[:4] in MODIFIED_MAGICS


def read_pcap(inp: Input, log: WarningLog, chunk_size: int, ports: RtuPorts = RtuPorts(),
              only: tuple[str, str, str] | None = None, span: Span | None = None, where: str = "") -> PcapRecords:
    """`ports`: a network link's RTU ports; `only`: the one connection read, over its `span` of the file's
    records when given (sources/ethernet.py), `where` said before its payloads' warnings (its bus's title)."""
    return PcapRecords(inp, log, chunk_size, ports, only, span, where)


class PcapRecords:
    """The chunks of a pcap's records (an iterator); `blocks` reads the rest in bulk (accel/records.py).
    `recorded_until`, once read: the time of its last timed record, empty or not (None: none), when the tap
    was last recording (Dissector's `recorded`; the bulk reader sets it for the records it reads)."""

    def __init__(self, inp: Input, log: WarningLog, chunk_size: int, ports: RtuPorts = RtuPorts(),
                 only: tuple[str, str, str] | None = None, span: Span | None = None, where: str = "") -> None:
        self.ports, self.only, self.span = ports, only, span
        self.payload_log = Where(log, where) if where else log  # (a connection's record warnings: its bus named)
        self.transport: Transport | None = None  # a network link's (RTU over TCP/UDP)
        self.inp = inp
        self.log = log
        self.chunk_size = chunk_size
        self.record = 0
        self.between = False  # the last chunk given ended a record: the next bytes are a record header
        self.holding = False  # a record's header is read but its chunks are not all given yet
        self.order, self.units, self.linktype, self.snaplen = "<", 1_000_000, 0, 0
        self.extra = 0  # record header bytes after the standard 16 (modified pcap)
        self.recorded_until: Stamp | None = None
        self.numbered = 0  # the record whose chunks are given (the first, held at the epoch, after the second is read)
        self.rtac_times: PacketTimes | None = None  # an RTAC link's packet marks (_stamped)
        self._packet: int | None = None  # the time of the packet before the RTAC record read (ns)
        self._header()  # (at once: its time units set the time column's decimals before any record)
        seekable = getattr(inp.stream, "seekable", None)  # (not a compressed file's: passed over unread)
        if self.transport is not None and span is not None and seekable and seekable():  # (its first record)
            inp.seek(span[2] - RECORD_HEADER_SIZE - self.extra)
            self.record = span[0] - 1
        self._chunks = self.records(inp)

    def __iter__(self) -> PcapRecords:
        return self

    def __next__(self) -> Chunk:
        chunk = next(self._chunks)
        # (accel/records.py reads the rest in bulk from between two records: standard headers only)
        self.between = chunk.boundary and not self.holding and not self.extra
        return chunk

    @property
    def packet_times(self) -> PacketTimes | None:
        """A network link's packet times (sources/ethernet.py), the time column's references."""
        return self.rtac_times if self.transport is None else self.transport.times

    @property
    def packet_number(self) -> int:
        """The record number (tshark's frame.number) of the record whose chunks are being given (-T fields'
        `record`: sources/trail.py)."""
        return self.numbered

    @property
    def packet_total(self) -> int:
        """The records read (all of them, once read)."""
        return self.record

    @property
    def time_units(self) -> int:
        """Its records' time units a second (render/timefmt.py column_digits)."""
        return self.units

    def _header(self) -> None:
        inp = self.inp
        header = inp.read(FILE_HEADER_SIZE)
        magic = header[:4]
        if not is_pcap(magic):
            raise SourceError(f"{inp.name}: not a pcap file (magic {magic.hex() or 'missing'})")
        if len(header) < FILE_HEADER_SIZE:
            raise SourceError(
                f"{inp.name}: truncated pcap file header ({len(header)} of {FILE_HEADER_SIZE} bytes)"
            )
        if magic in MODIFIED_MAGICS:
            self.order, self.extra = MODIFIED_MAGICS[magic], MODIFIED_EXTRA
        else:
            self.order, self.units = MAGICS[magic]
        _major, _minor, _zone, _sigfigs, self.snaplen, network = struct.unpack(self.order + "HHiIII", header[4:])
        # The upper bits of the link-type field hold FCS information, irrelevant to a serial line.
        self.linktype = network & 0xFFFF
        check_linktype(inp.name, self.linktype)
        if self.linktype in NETWORK_LINKTYPES:
            self.transport = Transport(inp.name, self.ports, self.only, span=self.span)
        if self.linktype == LINKTYPE_RTAC_SERIAL:
            self.rtac_times = PacketTimes()
        # (read ahead from a file alone, not a live feed: wiretap reads a variant's file only then, "that type
        # of pcap file can't be read from a pipe")
        if self.units == 1_000_000 and rereadable(inp):
            self.extra = self._variant(MODIFIED_VARIANTS if magic in MODIFIED_MAGICS else STANDARD_VARIANTS)

    def _variant(self, extras: tuple[int, ...]) -> int:
        """The record header's extra bytes, as wiretap's libpcap.c guesses the variant a magic leaves open: the
        first whose first two record headers look sane (else the least wrong), read ahead and given back.
        Read as standard headers, an ss990417 file's records took their 8 extra bytes as serial bytes and
        went astray from the second record on (a fraction of a second of 1767225600, a record of 1.7 GB)."""
        inp = self.inp
        head = inp.read(RECORD_HEADER_SIZE + max(extras))
        first = min(struct.unpack_from(self.order + "I", head, 8)[0], MAX_PACKET) if len(head) >= 12 else 0
        ahead = head + inp.read(first + RECORD_HEADER_SIZE + max(extras))
        inp.unread(ahead)
        faults: list[int] = []
        for extra in extras:
            # (libpcap_try: a first header at fault tells alone, and alike for every variant: its 16 bytes are the
            # standard ones; a file ending before the second header is this variant's)
            fault = self._faults(ahead, 0)
            following = RECORD_HEADER_SIZE + extra + first
            if not fault and len(ahead) >= following + RECORD_HEADER_SIZE + extra:
                fault = self._faults(ahead, following)
            if not fault:
                return extra
            faults.append(fault)
        return extras[faults.index(min(faults))]

    def _faults(self, data: bytes, at: int) -> int:
        """What is wrong with the record header at `at` read as a standard one (libpcap_try_header)."""
        if len(data) < at + RECORD_HEADER_SIZE:
            return 0
        _seconds, fraction, captured, original = struct.unpack_from(self.order + "IIII", data, at)
        return ((fraction >= self.units) + (captured > MAX_PACKET) + (original > 64 << 20)
                + (0 < self.snaplen < captured) + (captured > original))

    def records(self, inp: Input) -> Iterator[Chunk]:
        """The chunks of the records `inp` holds from its position on."""
        log = self.log
        record_header = struct.Struct(self.order + "IIII" + "x" * self.extra)
        held = EpochRecord(self.chunk_size)
        while True:
            head = inp.read(record_header.size)
            if not head:
                self.numbered = 1 if held.chunks is not None else self.numbered
                yield from held.release(False)
                if self.transport is not None and self.record:
                    self.transport.finish(log.warn)
                if self.record == 0:  # (tshark shows nothing: say why the output is empty)
                    log.warn("empty", f"{inp.name}: the capture holds no records")
                return
            self.record += 1
            if len(head) < record_header.size:
                self.numbered = 1
                yield from held.release(False)
                log.warn(
                    "truncated input",
                    f"record {self.record}: the capture ends inside its header "
                    f"({len(head)} of {record_header.size} bytes)",
                )
                return
            seconds, fraction, captured, original = record_header.unpack(head)
            corrupt = fraction >= self.units
            if corrupt:
                log.warn(CORRUPT_STAMPS, f"record {self.record}: {fraction_error(fraction, self.units)}")
            if captured < original and self.transport is None:  # (a network record's: its payload's, common.py)
                log.warn(
                    "records captured in part",
                    f"record {self.record}: only {captured} of its {original} bytes were captured",
                )
            if 0 < self.snaplen < captured:  # (a damaged header or record: libpcap captures at most snaplen)
                log.warn(
                    "records longer than the snapshot length",
                    f"record {self.record}: {captured} bytes, more than the file header's snapshot length "
                    f"({self.snaplen}): a damaged file?",
                )
            time = None if corrupt else Stamp.from_parts(seconds, fraction, self.units)
            if self.transport is not None:
                self.numbered = self.record  # (a network link: the RTU ports' payloads alone, as records)
                for chunk in record_chunks(inp, captured, time, self.linktype, self.record, self.payload_log,
                                           self.chunk_size, original=original, transport=self.transport):
                    self.recorded_until = time if time is not None else self.recorded_until
                    yield chunk
                if self.transport.past(self.record):  # (the connection read has no record after)
                    return
                continue
            chunks = record_chunks(inp, captured, time, self.linktype, self.record, log, self.chunk_size,
                                   self._stamped if self.linktype == LINKTYPE_RTAC_SERIAL else None, original)
            epoch = not (seconds or fraction)
            if not epoch and not corrupt and self.linktype != LINKTYPE_RTAC_SERIAL:  # (an RTAC's is in its bytes)
                self.recorded_until = time
            if epoch and self.record == 1 and self.linktype != LINKTYPE_RTAC_SERIAL and held.hold(captured, chunks):
                continue
            if held.chunks is not None:
                self.holding = True
                self.numbered = 1
                yield from held.release(within_day_zero(epoch, seconds) and not corrupt)
                self.holding = False
            self.numbered = self.record
            if epoch and self.linktype != LINKTYPE_RTAC_SERIAL:
                # (-w's untimed record: see EpochRecord; an RTAC record carries its own time)
                chunks = record_chunks(inp, captured, None, self.linktype, self.record, log, self.chunk_size,
                                       original=original)
            if self.rtac_times is None:
                yield from chunks
                continue
            self._packet = None  # (_stamped sets it once the header is read: none when it is cut or corrupt)
            for chunk in chunks:
                self.rtac_times.taken(len(chunk.data), self._packet)
                yield chunk


    def _stamped(self, time: Stamp) -> None:
        """An RTAC record's own time (its header's), data or not: the tap was recording then, and a packet tshark
        shows (common.py rtac_mark)."""
        self.recorded_until = time
        self._packet = rtac_mark(self.rtac_times, time)


def empty_records(buffer: bytes, position: int, end: int, reader: PcapRecords, offset: int) -> list[tuple[int, int | None]]:
    """The empty records among the standard ones of `buffer` from `position` to `end` (a bulk scan passed over
    them: accel/records.py), as (stream offset, time in ns or None), `offset` the stream offset at `position`:
    -w writes them again (sources/trail.py), as the records this reader gives (common.py record_chunks)."""
    header = struct.Struct(reader.order + "IIII")
    found: list[tuple[int, int | None]] = []
    while position + RECORD_HEADER_SIZE <= end:
        seconds, fraction, captured, original = header.unpack_from(buffer, position)
        if captured == 0 and original == 0:
            timed = (seconds or fraction) and fraction < reader.units
            found.append((offset, Stamp.from_parts(seconds, fraction, reader.units).ns if timed else None))
        position += RECORD_HEADER_SIZE + captured
        offset += captured
    return found


CORRUPT_STAMPS = "corrupt time stamps"


def fraction_error(fraction: int, units: int) -> str:
    """Why a record's fraction of a second is not taken: its bytes are decoded untimed, the file is not
    refused (tshark 4.0 reads it, showing the stamp unnormalised: 0.1385347 s for 4,000,000,000 us;
    wiretap's libpcap.c takes a fraction >= 1 s only as a hint when it guesses a file's variant)."""
    return (f"fraction of a second {fraction} is not below {units} (1 s in the file's units): "
            "a corrupt time stamp? Its bytes are decoded untimed")


DAY_ZERO_END = 86_400  # s: where a time-of-day log of day 0 (1970-01-01) ends


def within_day_zero(epoch: bool, seconds: int) -> bool:
    """Does a second record at `seconds` since the epoch make the first, at the epoch, a timed record
    (EpochRecord)? Only within day 0: a record at a real date after it says the first was untimed."""
    return not epoch and seconds < DAY_ZERO_END


class EpochRecord:
    """A capture's first record when stamped at the epoch, held until the second record's time says
    what it is. vw3-decode -w writes untimed input at the epoch, every record; a capture that starts at
    1970-01-01 00:00:00 (a time-of-day log of day 0) has later times of that day after it. So the first
    record at the epoch is timed when the second record is not at the epoch but within day 0, untimed
    otherwise (an untimed record before a real date's is not 54 years of silence); records after the
    first at the epoch are untimed. Only a record of one chunk is held (memory stays bounded): a longer
    one at the epoch is untimed."""

    def __init__(self, chunk_size: int) -> None:
        self.chunk_size = chunk_size
        self.chunks: list[Chunk] | None = None

    def hold(self, captured: int, chunks: Iterator[Chunk]) -> bool:
        """Hold a first record at the epoch (its `chunks`, not yet read, timed) when it is one chunk;
        False when there is nothing to hold (then `chunks` is unread)."""
        if not captured or captured > self.chunk_size:
            return False
        self.chunks = []
        for chunk in chunks:  # (one by one: a record cut short keeps what was read, for release)
            self.chunks.append(chunk)
        return True

    def release(self, timed: bool) -> Iterator[Chunk]:
        """The held chunks: at the epoch when the record after is `timed`, untimed otherwise."""
        chunks, self.chunks = self.chunks, None
        for chunk in chunks or ():
            yield chunk if timed else replace(chunk, time=None)  # (a NotedChunk keeps its comments)
