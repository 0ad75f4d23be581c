"""pcapng files: sections in either byte order, several interfaces, each with its link type and
timestamp resolution (if_tsresol) and offset (if_tsoffset), and its texts (if_name, if_description:
what `vw3-decode --live -w` writes the serial settings in, framing/linespeed.py reads the speed there).

Packets come from Enhanced (EPB), Simple (SPB, no timestamp) and obsolete Packet blocks (OPB).
A packet's comments (opt_comment: `editcap -a`, Wireshark's Packet Comment) ride on its record's last
chunk (sources/common.py NotedChunk), except the ones vw3-decode writes itself (sources/trail.py
own_comment). Blocks that carry no packet (name resolution, statistics, secrets, custom) are passed over; blocks
of unknown type are skipped with a warning. Bodies are read piece by piece, so memory stays
bounded whatever block sizes the file claims.
"""
from __future__ import annotations

import functools
import io
import os
import stat
import struct
from collections.abc import Iterator
from dataclasses import replace

from dissector.model import Chunk, Stamp
from dissector.sources.common import (
    Where,
    LINKTYPE_NAMES,
    LINKTYPE_RTAC_SERIAL,
    rtac_mark,
    LINKTYPE_USER0,
    Input,
    NotedChunk,
    PartChunk,
    SourceError,
    WarningLog,
    check_linktype,
    outside_time_range,
    record_chunks,
    rereadable,
)
from dissector.sources.ethernet import NETWORK_LINKTYPES, PacketTimes, RtuPorts, Span, Transport
from dissector.sources.pcap import EpochRecord, within_day_zero
from dissector.sources.trail import own_comment
from dissector.sources.pcapng_blocks import (
    BYTE_ORDER_MAGIC,
    EPB,
    IDB,
    MAX_HEADER_BLOCK,
    NO_PACKET_BLOCKS,
    OPB,
    OPT_COMMENT,
    SHB_MAGIC,
    SPB,
    Interface,
    _interface,
    _options,
    section_ordinal,
    is_pcapng,
    serial,
)

class _Reader:
    """`only`: the ordinal of the one interface whose packets are read (interfaces numbered in the
    order the file describes them, across sections); the others' packets are passed over."""

    def __init__(self, inp: Input, log: WarningLog, chunk_size: int, first_interface: bool = False,
                 only: int | None = None, tell_skipped: bool = True, where: str = "",
                 ports: RtuPorts = RtuPorts(), connection: tuple[str, str, str] | None = None,
                 span: Span | None = None, networks: bool = False, beside: bool = False) -> None:
        self.inp = inp
        # `networks`: the network interfaces' packets alone are read (a serial interface's passed over, unsaid: its
        # own bus reads them); `beside`: they are other buses' (a serial bus passes them over, unsaid)
        self.networks, self.beside = networks, beside
        # A network interface's packets: the RTU ports' payloads (sources/ethernet.py; `connection`: its one read,
        # its records alone parsed, within `span`)
        self.transport = Transport(inp.name, ports, connection, span=span)
        self.networked = False  # a network interface's packet was read
        self.marks = False  # a serial interface's packets mark their times (read_pcapng `shared`)
        self.packet: int | None = None  # the time of the packet before the one read (ns), once marked
        # The warnings that number a record: `where` (the bus's title, `file: if_name`) first when the file is
        # read once per interface, each numbering its own records ("record 2" alone sent the reader to the
        # first bus's, or to tshark's frame 2).
        self.record_log = Where(log, where) if where else log
        self.only = only
        self.tell_skipped = tell_skipped  # count the packets of interfaces not read (one bus of several says)
        self.described: list[Interface] = []  # the file's interfaces described so far, all sections (section_ordinal)
        self.ordinals: list[int] = []  # the section's interfaces' ordinals in the file
        # stop once the first serial interface is described (an Ethernet one beside it is no bus)
        self.first_interface = first_interface
        self.log = log
        self.chunk_size = chunk_size
        self.order = "<"
        self.interfaces: list[Interface] = []
        self.record = 0
        # Packet blocks met, every interface's (tshark's frame.number of the last), and the number of the packet whose
        # chunks are given (its first, held at the epoch, after the second is read): -T fields' `record` (trail.py).
        self.packets = self.numbered = self.held_number = 0
        self.used_interfaces: set[int] = set()
        self.held = EpochRecord(chunk_size)  # the first packet, at the epoch, until the next says (pcap.py)
        # The time of the last timed packet read, any interface's, empty or not: the tap was recording then
        # (read_pcapng's recorded_until).
        self.last_time: Stamp | None = None
        # Packets of interfaces carrying no serial bytes (an Ethernet tap beside the serial one), passed
        # over: ordinal -> [linktype, records, bytes], told once at the end (skipped_warnings).
        self.skipped: dict[int, list[int]] = {}
        self.unshown = 0  # packet comments of records with no serial byte: no item shows them (comment_warning)
        self.packeted = False  # a packet block was met (an interface described after one: spans not sought)

    def run(self) -> Iterator[Chunk]:
        inp = self.inp
        first = True
        while True:
            start = inp.position
            head = inp.read(8)
            if not head:
                return
            if len(head) < 8:
                self.log.warn("truncated input", f"the capture ends inside a block header at byte {start}")
                return
            if head[:4] == SHB_MAGIC:
                self.transport.seekable = self.transport.seekable and not self.packeted
                if not self._section(head, start):
                    return
                first = False
                continue
            if first:
                raise SourceError(f"{inp.name}: not a pcapng file (no section header block)")
            block_type, total = struct.unpack(self.order + "II", head)
            if total < 12 or total % 4:
                raise SourceError(
                    f"{inp.name}: block at byte {start} has an invalid length {total} (corrupt file?)"
                )
            body_length = total - 12
            if block_type == IDB:
                body = self._body(body_length, start, "interface description")
                if body is None:
                    return
                self.interfaces.append(_interface(body, self.order, inp.name))
                self.transport.seekable = self.transport.seekable and not self.packeted
                self.ordinals.append(section_ordinal(self.interfaces[-1], self.described, self.ordinals))
                if self.first_interface and serial(self.interfaces[-1].linktype):
                    return
            elif block_type in (EPB, OPB, SPB) and self._counted() and self._jump(start):
                self.packets = self.record  # (the span's first packet is counted as it is read)
                continue
            elif block_type in (EPB, OPB, SPB) and self._passed_over():
                if inp.skip(body_length) < body_length:
                    self.log.warn("truncated input", f"the capture ends inside the packet block at byte {start}")
                    return
            elif block_type in (EPB, OPB):
                yield from self._packet(block_type, body_length, start)
            elif block_type == SPB:
                yield from self._simple(body_length, start)
            else:
                if block_type not in NO_PACKET_BLOCKS:
                    self.log.warn(
                        f"pcapng blocks of type {block_type:#x}",
                        f"skipped a pcapng block of unknown type {block_type:#010x} at byte {start}",
                    )
                if inp.skip(body_length) < body_length:
                    self.log.warn("truncated input", f"the capture ends inside the block at byte {start}")
                    return
            if not self._trailer(total, start):
                return

    def _counted(self) -> bool:
        """A packet block is met: counted (self.packets). True."""
        self.packets += 1
        return True

    def _jump(self, start: int) -> bool:
        """Go straight to the span of the one connection read from a packet block before it (its offset: the
        block's, -1 when an interface is described among the packets), as a pcap's bus does: passing over each
        block before it, 1,600 buses of one poll took 21.8 s, quadratic (1.4 s as a pcap)."""
        self.packeted = True
        span = self.transport.span
        seekable = getattr(self.inp.stream, "seekable", None)  # (not a compressed file's: passed over unread)
        if span is None or not 0 <= start < span[2] or self.record + 1 >= span[0] or not (seekable and seekable()):
            return False
        self.inp.seek(span[2])
        self.record = span[0] - 1
        return True

    def _passed_over(self) -> bool:
        """A packet not read at all: the interfaces alone are sought (first_interface), or it comes before the
        span of the one connection read (each packet of a network capture is numbered: sources/ethernet.py)."""
        if self.first_interface:
            return True
        if self.transport.outside(self.record + 1) and self.transport.span is not None:
            if self.record + 1 < self.transport.span[0]:
                self.record += 1
                return True
        return False

    # -- blocks ------------------------------------------------------------------------------
    def _section(self, head: bytes, start: int) -> bool:
        """Read a section header block; False when the input ends inside it."""
        magic = self.inp.read(4)
        if len(magic) < 4:
            raise SourceError(f"{self.inp.name}: truncated section header block at byte {start}")
        if magic == struct.pack("<I", BYTE_ORDER_MAGIC):
            self.order = "<"
        elif magic == struct.pack(">I", BYTE_ORDER_MAGIC):
            self.order = ">"
        else:
            raise SourceError(f"{self.inp.name}: section header at byte {start}: bad byte-order magic")
        total = struct.unpack(self.order + "I", head[4:])[0]
        if total < 28 or total % 4:
            raise SourceError(f"{self.inp.name}: section header at byte {start} has length {total}")
        # A new section starts its own list of interfaces.
        self.interfaces = []
        self.ordinals = []
        if self._body(total - 16, start, "section header") is None:
            return False
        return self._trailer(total, start)

    def _body(self, length: int, start: int, what: str) -> bytes | None:
        if length > MAX_HEADER_BLOCK:
            raise SourceError(f"{self.inp.name}: {what} block at byte {start} claims {length} bytes")
        body = self.inp.read(length)
        if len(body) < length:
            self.log.warn("truncated input", f"the capture ends inside the {what} block at byte {start}")
            return None
        return body

    def _trailer(self, total: int, start: int) -> bool:
        trailer = self.inp.read(4)
        if len(trailer) < 4:
            self.log.warn("truncated input", f"the capture ends inside the block at byte {start}")
            return False
        if struct.unpack(self.order + "I", trailer)[0] != total:
            raise SourceError(
                f"{self.inp.name}: block at byte {start}: trailing length differs from {total} "
                "(corrupt file?)"
            )
        return True

    def _other(self, index: int, space: int, start: int, captured: int) -> bool:
        """Whether the packet is another interface's than the one read (`only`), or one of an interface
        that carries no serial bytes (counted: skipped_warnings) while another interface does; its
        `space` bytes are then passed over."""
        linktype = self.interfaces[index].linktype if index < len(self.interfaces) else None
        unreadable = linktype is not None and not serial(linktype)
        if self.networks:
            if linktype is None or not serial(linktype):
                return False
        elif unreadable and any(serial(interface.linktype) for interface in self.interfaces):
            if self.tell_skipped and not (self.beside and linktype in NETWORK_LINKTYPES):
                linktype = self.interfaces[index].linktype
                counts = self.skipped.setdefault(self.ordinals[index], [linktype, 0, 0])
                counts[1] += 1
                counts[2] += captured
        elif self.only is None or (index < len(self.ordinals) and self.ordinals[index] == self.only):
            return False
        if self.inp.skip(space) < space:
            self.log.warn("truncated input", f"the capture ends inside the packet block at byte {start}")
            raise _Ended()
        return True

    def _interface_for(self, index: int, start: int) -> Interface:
        if index >= len(self.interfaces):
            raise SourceError(
                f"{self.inp.name}: packet at byte {start} refers to interface {index}, "
                f"but {len(self.interfaces)} are described"
            )
        interface = self.interfaces[index]
        check_linktype(self.inp.name, interface.linktype, f"interface {index}: ")
        if index not in self.used_interfaces and self.only is None:
            self.used_interfaces.add(index)
            if len(self.used_interfaces) == 2:
                # (a file is read once per interface, each its own bus: cli.py _inputs; a pipe cannot be)
                self.log.warn(
                    "interfaces",
                    "packets come from several interfaces; their bytes are decoded as one stream "
                    "(vw3-decode FILE decodes each interface as its own bus: save standard input to a file)",
                )
        return interface

    def _packet(self, block_type: int, body_length: int, start: int) -> Iterator[Chunk]:
        inp = self.inp
        fixed = inp.read(20)
        if len(fixed) < 20:
            self.log.warn("truncated input", f"the capture ends inside the packet block at byte {start}")
            return
        if block_type == EPB:
            index, high, low, captured, original = struct.unpack(self.order + "IIIII", fixed)
        else:
            index, _drops, high, low, captured, original = struct.unpack(self.order + "HHIIII", fixed)
        if 20 + captured > body_length:
            raise SourceError(
                f"{inp.name}: packet block at byte {start}: {captured} bytes do not fit in the block"
            )
        epoch = not (high or low)
        if self._other(index, body_length - 20, start, captured):
            if not epoch and index < len(self.interfaces):
                self._recorded(self.interfaces[index], high << 32 | low)
            return
        interface = self._interface_for(index, start)
        self.transport.block = start  # (a connection's span starts at its first packet's block)
        seconds, fraction = divmod(high << 32 | low, interface.units)
        time = Stamp.from_parts(interface.offset + seconds, fraction, interface.units)
        outside = outside_time_range(time.ns, interface.offset) if not epoch or self.record == 0 else None
        if outside is not None:
            raise SourceError(f"{inp.name}: packet block at byte {start}: {outside}")
        if not epoch and interface.linktype != LINKTYPE_RTAC_SERIAL and interface.linktype not in NETWORK_LINKTYPES:
            self.last_time = time  # (an RTAC record's time is in its bytes; a network packet's if it is the bus's)
        self.numbered = self.held_number
        yield from self.held.release(within_day_zero(epoch, seconds))
        self.numbered = self.packets
        chunks = self._data(captured, original, time, interface, body_length - 20, start)
        if (epoch and self.record == 0 and interface.linktype != LINKTYPE_RTAC_SERIAL
                and self.held.hold(captured, chunks)):
            self.held_number = self.packets
            return
        if epoch:
            # vw3-decode -w writes records at the epoch when its input had no times: untimed (pcap.py
            # EpochRecord); an RTAC record carries its own time.
            chunks = self._data(captured, original, None, interface, body_length - 20, start)
        yield from chunks
        if interface.linktype in NETWORK_LINKTYPES and self.transport.past(self.record):
            raise _Ended()  # (the connection read has no record after: sources/ethernet.py Transport.span)

    def skipped_warnings(self) -> None:
        """One line per interface whose packets were passed over, with what they held (every byte of the
        input accounted for)."""
        ports = self.transport.ports
        for ordinal, (linktype, records, length) in sorted(self.skipped.items()):
            label = LINKTYPE_NAMES.get(linktype, "not a serial line")
            # (--tcp-port/--udp-port given: a file's connections on them are buses, read beside the serial ones; none
            # here, or standard input, read once: said rather than nothing done unsaid)
            unread = ""
            if linktype in NETWORK_LINKTYPES and ports != RtuPorts():
                unread = (f"; no TCP or UDP payload on its {ports.text()}" if rereadable(self.inp.name) else
                          f"; its {ports.text()} not read in one stream beside a serial interface "
                          "(vw3-decode FILE reads its connections as buses of their own)")
            self.log.warn(
                "skipped interfaces",
                f"interface {ordinal}: linktype {linktype} ({label}) carries no serial bytes: "
                f"{records} record{'s' if records != 1 else ''} ({length} bytes) skipped{unread}",
            )

    def _recorded(self, interface: Interface, stamp: int) -> None:
        """Another interface's timed packet was recorded (passed over). An RTAC record's time is in its
        bytes: that interface's chunks carry it (Dissector.feed)."""
        seconds, fraction = divmod(stamp, interface.units)
        time = Stamp.from_parts(interface.offset + seconds, fraction, interface.units)
        if outside_time_range(time.ns, interface.offset) is None:  # (else the record's reading refuses it)
            self.transport.times.packet(time.ns)  # (a packet tshark shows: a network bus's time column counts it)
            if interface.linktype != LINKTYPE_RTAC_SERIAL:
                self.last_time = time

    def _simple(self, body_length: int, start: int) -> Iterator[Chunk]:
        raw = self.inp.read(4)
        if len(raw) < 4:
            self.log.warn("truncated input", f"the capture ends inside the packet block at byte {start}")
            return
        original = struct.unpack(self.order + "I", raw)[0]
        if self._other(0, body_length - 4, start, min(original, body_length - 4)):
            return
        interface = self._interface_for(0, start)
        self.transport.block = start
        captured = min(original, body_length - 4)
        if interface.snaplen:
            captured = min(captured, interface.snaplen)
        # A simple packet block has no timestamp.
        self.numbered = self.held_number
        yield from self.held.release(False)
        self.numbered = self.packets
        yield from self._data(captured, original, None, interface, body_length - 4, start, options=False)

    def _data(
        self, captured: int, original: int, time: float | None, interface: Interface,
        space: int, start: int, options: bool = True,
    ) -> Iterator[Chunk]:
        """The record's chunks; `options`: its block's options follow the packet data, padded to 4 bytes
        (EPB, OPB; not SPB), and the packet comments among them go on its last chunk (held back until
        they are read: they come after the data)."""
        self.record += 1
        if captured < original and interface.linktype not in NETWORK_LINKTYPES:  # (a payload's: common.py)
            self.record_log.warn(
                "records captured in part",
                f"record {self.record}: only {captured} of its {original} bytes were captured",
            )
        before = self.inp.position
        last: Chunk | None = None
        rtac = self._stamped if interface.linktype == LINKTYPE_RTAC_SERIAL else None
        network = interface.linktype in NETWORK_LINKTYPES
        self.networked = self.networked or network
        # (an RTAC record's packet is marked at its header's time once read, _stamped: common.py rtac_mark)
        mark = self.marks and interface.linktype == LINKTYPE_USER0
        self.packet = self.transport.times.packet(getattr(time, "ns", None)) if mark else None
        for chunk in record_chunks(
            self.inp, captured, time, interface.linktype, self.record, self.record_log, self.chunk_size, rtac,
            original, self.transport if network else None,
        ):
            if mark or rtac:
                self.transport.times.taken(len(chunk.data), self.packet)
            if network and time is not None:  # (the plugin sees it: it was recording then)
                self.last_time = time
            if last is not None:
                yield last
            last = chunk
        if self.inp.position - before < captured:
            if last is not None:
                yield last
            raise _Ended()
        rest = space - captured
        padding = -captured % 4
        if options and padding < rest <= MAX_HEADER_BLOCK:
            tail = self.inp.read(rest)
            comments = self._comments(tail[padding:]) if len(tail) == rest else ()
            read = len(tail)
        else:
            comments, read = (), self.inp.skip(rest)
        if comments and isinstance(last, PartChunk):  # (captured in part: it stays the framers' cut)
            last = replace(last, comments=comments)
        elif comments and last is not None:
            last = NotedChunk(last.data, last.time, last.boundary, self.record, comments)
        if comments and (last is None or not last.data):  # (an empty record's go on with it for -w alone)
            self.unshown += len(comments)
        if last is not None:
            yield last
        if read < rest:
            self.log.warn("truncated input", f"the capture ends inside the packet block at byte {start}")
            raise _Ended()

    def _stamped(self, time: Stamp) -> None:
        """An RTAC record's own time (its header's), data or not: the tap was recording then, and a packet tshark
        shows (common.py rtac_mark)."""
        self.last_time = time
        self.packet = rtac_mark(self.transport.times, time)

    def _comments(self, options: bytes) -> tuple[str, ...]:
        """The packet's comments (opt_comment), but those vw3-decode wrote of its own decode."""
        texts = (value.decode("utf-8", "replace") for code, value in _options(options, self.order)
                 if code == OPT_COMMENT)
        return tuple(text for text in texts if not own_comment(text))

    def comment_warning(self) -> None:
        """Comments of records with no serial byte (an empty record, an RTAC header alone): no item is
        there to show them."""
        if self.unshown:
            self.log.warn(
                "packet comments",
                f"{self.unshown} packet comment{'s' if self.unshown != 1 else ''} on records with no serial "
                "byte not shown (tshark -V shows them)",
            )


class _Ended(Exception):
    """The input ended inside a block (already reported): stop reading."""


def first_interface(path: str) -> Interface | None:
    """first_interface_of, read once for a file's buses (each bus asked: 1,600 connections read a network pcapng's
    head, up to HEAD_BYTES and no serial interface to stop at, 1,600 times)."""
    try:
        status = os.stat(path)
    except OSError:
        return None
    return _first_interface(path, status.st_size, status.st_mtime_ns)


@functools.lru_cache(maxsize=8)
def _first_interface(path: str, _size: int, _mtime: int) -> Interface | None:
    return first_interface_of(path)


def first_interface_of(path: str) -> Interface | None:
    """The first serial interface a pcapng file describes (else its first); None for another format, or a
    file that cannot say.

    Read from the file's first blocks (the interface precedes the packets it carries), at most
    HEAD_BYTES, so asking costs the same whatever the capture's size. Not from a FIFO: its bytes are the
    decode's (read here, they would be gone).
    """
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
        with open(path, "rb") as stream:
            head = stream.read(HEAD_BYTES)
    except OSError:
        return None
    if not is_pcapng(head):
        return None
    reader = _Reader(Input(io.BytesIO(head), path), WarningLog(), 1 << 16, first_interface=True)
    try:
        for _chunk in reader.run():
            break  # a packet before any interface: not a valid file, nothing to say
    except (SourceError, _Ended):
        pass
    serials = [interface for interface in reader.interfaces if serial(interface.linktype)]
    return (serials or reader.interfaces or [None])[0]


HEAD_BYTES = 4 * MAX_HEADER_BLOCK


class PcapngChunks:
    """The chunks of a pcapng's packets, and `recorded_until`: the time of its last timed packet, of any
    interface, empty or not (None: none), once read. The tap recorded every line until then: a request
    near the end of one interface's bus waited as long as the other interfaces' records went on
    (Dissector's `recorded`)."""

    def __init__(self, reader: _Reader) -> None:
        self._reader = reader
        self._chunks = self._read()
        self.damage: SourceError | None = None  # where the file is damaged after its first packet, once read

    def __iter__(self) -> Iterator[Chunk]:
        return self._chunks  # (the one generator: a loop that stops early resumes where it stopped)

    def __next__(self) -> Chunk:
        return next(self._chunks)

    @property
    def recorded_until(self) -> Stamp | None:
        return self._reader.last_time

    @property
    def packet_number(self) -> int:
        """The file's packet number (tshark's frame.number) of the record whose chunks are being given."""
        return self._reader.numbered

    @property
    def packet_total(self) -> int:
        """The packet blocks read (all of them, once read)."""
        return self._reader.packets

    @property
    def transport(self) -> Transport | None:
        """Its network interfaces' reading (sources/ethernet.py), once one's packet is read; else None."""
        return self._reader.transport if self._reader.networked else None

    @property
    def packet_times(self) -> PacketTimes | None:
        """Its network interfaces' packet times (sources/ethernet.py) when RTU ports are given, but for a serial
        interface's bus (`only`); a serial bus's of a file with packets on several interfaces (read_pcapng)."""
        reader = self._reader
        networked = reader.transport.ports != RtuPorts() and reader.only is None
        return reader.transport.times if networked or reader.marks or self._rtac() else None

    def _rtac(self) -> bool:
        """The bus read is an RTAC interface's (its packets marked: common.py rtac_mark), as far as can be told
        before its first packet: else a file's first serial interface, read ahead (first_interface_of)."""
        reader = self._reader
        serials = [interface for interface in reader.interfaces if serial(interface.linktype)]
        first = serials[0] if serials else first_interface_of(reader.inp.name)
        return getattr(first, "linktype", None) == LINKTYPE_RTAC_SERIAL

    @property
    def time_units(self) -> int | None:
        """The finest time units a second (if_tsresol) of the interfaces described so far, of the one read
        (`only`) if described; None before any (render/timefmt.py column_digits)."""
        reader = self._reader
        described = list(zip(reader.ordinals, reader.interfaces))
        units = [interface.units for ordinal, interface in described if reader.only in (None, ordinal)]
        return max(units, default=None)

    def _read(self) -> Iterator[Chunk]:
        try:
            yield from self._reader.run()
        except _Ended:
            pass
        except SourceError as error:
            if self._reader.record == 0:
                raise
            # (damage after packets: the chunks end, the Source raises it after them, or the decode once it has
            # shown them, as tshark shows them: reader.py Source.defer_damage; before, nothing was shown)
            self.damage = error
        if self._reader.held.chunks is not None:
            self._reader.numbered = self._reader.held_number
        yield from self._reader.held.release(False)
        reader = self._reader
        if reader.networked:
            reader.transport.finish(reader.log.warn)
        if reader.record == 0 and not reader.skipped and reader.only is None:
            # (tshark shows nothing: say why the output is empty)
            reader.log.warn("empty", f"{reader.inp.name}: the capture holds no packets")
        self._reader.skipped_warnings()
        self._reader.comment_warning()


def read_pcapng(inp: Input, log: WarningLog, chunk_size: int, only: int | None = None,
                tell_skipped: bool = True, where: str = "", ports: RtuPorts = RtuPorts(),
                connection: tuple[str, str, str] | None = None, span: Span | None = None, networks: bool = False,
                beside: bool = False, shared: bool = False) -> PcapngChunks:
    """The chunks of a pcapng's packets (`only`: of that interface alone, by its ordinal; `tell_skipped`:
    warn of the interfaces carrying no serial bytes; `where`: said before a warning that numbers a record;
    `ports`, `connection`: a network interface's RTU ports and the one connection read, sources/ethernet.py;
    `networks`, `beside`: the network interfaces' packets alone are read, or passed over as other buses';
    `shared`, or `only`: packets come from several interfaces, the serial bus's time column counts them all,
    as tshark's frame.time_relative and frame.time_delta, where it counted its own items)."""
    reader = _Reader(inp, log, chunk_size, only=only, tell_skipped=tell_skipped, where=where, ports=ports,
                     connection=connection, span=span, networks=networks, beside=beside)
    reader.marks = only is not None or shared
    return PcapngChunks(reader)
