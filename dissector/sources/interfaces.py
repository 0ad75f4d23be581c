"""A pcapng with packets from several interfaces, read as one input per interface: each interface is its
own bus (what Wireshark writes capturing two serial lines at once), so each gets its own framer, pairing
and timing instead of one stream of both lines' bytes (bus A's answer paired with bus B's request, a
frame split over two records with the other bus's record between them read as noise).

A regular file is read once per interface (sources/pcapng.py `only`: the other interfaces' packets are
passed over), so memory stays bounded whatever the file's size; which interfaces carry packets is found
first by walking the block headers, seeking over the bodies. Standard input cannot be read twice: it
stays one stream, with the reader's warning saying so.

A pcap or pcapng of a network link carrying Modbus RTU over TCP/UDP (sources/ethernet.py) with several
connections on the RTU ports is read once per connection, each its own bus as the plugin keeps each
connection's stream (two masters polling one gateway: each answer paired with its own connection's request).
"""
from __future__ import annotations

import functools
import os
import stat
import struct
from dataclasses import dataclass, replace

from dissector.sources.common import LINKTYPE_USER0, Input, SourceError, WarningLog
from dissector.sources.ethernet import NETWORK_LINKTYPES, Connection, RtuPorts, Span
from dissector.sources.pcap import PcapRecords, is_pcap, read_pcap
from dissector.sources.pcapng import read_pcapng
from dissector.sources.pcapng_blocks import (EPB, IDB, MAX_HEADER_BLOCK, OPB, SHB_MAGIC, SPB, Interface, _interface,
                                             section_ordinal, serial)

SCAN_BUFFER = 1 << 20  # the walk's reads


@dataclass(slots=True)
class PacketInterface:
    ordinal: int  # in the order the file describes its interfaces, across sections (from 0)
    interface: Interface
    first: bool = False  # the file's first bus: it warns of the interfaces carrying no serial bytes
    connection: Connection | None = None  # RTU over TCP/UDP: the one connection of a network capture read
    span: Span | None = None  # its records' (sources/ethernet.py), read alone by a bus after the first

    def label(self) -> str:
        """The interface as a title names it: its if_name, else its description, else its number."""
        return self.interface.name or self.interface.description or f"interface {self.ordinal}"


def packet_interfaces(path: str, ports: RtuPorts = RtuPorts()) -> list[PacketInterface]:
    """The interfaces of a regular pcapng file that carry packets, in the file's order, or the connections on
    the RTU `ports` of a pcap or pcapng of a network link (connections); [] for anything else (another
    format, standard input, a file that cannot say: the one-stream reader reports it)."""
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return []
        status = os.stat(path)
        walked, described, networked, _carrying = _walked(path, status.st_size, status.st_mtime_ns)
        buses = [replace(bus) for bus in walked]
        if ports == RtuPorts() or buses and not networked:
            return buses
        if not buses:
            return connections(path, ports)
        # A serial interface beside a network one: the network interface's connections on the RTU ports are buses
        # too, numbered after the interfaces (before, its packets were passed over, where the plugin reads both).
        beside = [replace(bus, ordinal=described + bus.ordinal) for bus in connections(path, ports, 1)]
        return buses + beside if beside else buses
    except (OSError, struct.error, ValueError, SourceError):
        return []


def connections(path: str, ports: RtuPorts, least: int = 2) -> list[PacketInterface]:
    """The connections on the RTU ports of a pcap or pcapng file of a network link, in order of appearance,
    each a bus (titled by its transport and ends), when there are at least `least`; else []. The file is read
    once for it (records only: no decode), once for its size and time (the buses' Sources ask again)."""
    status = os.stat(path)
    return list(_connections(path, status.st_size, status.st_mtime_ns, ports, least))


@functools.lru_cache(maxsize=8)
def _connections(path: str, _size: int, _mtime: int, ports: RtuPorts, least: int) -> tuple[PacketInterface, ...]:
    with open(path, "rb") as stream:
        chunks = network_chunks(stream, path, WarningLog(), 1 << 16, ports, None)
        if isinstance(chunks, PcapRecords) and chunks.transport is None:  # (a serial pcap is not read here)
            return ()
        for _chunk in chunks:
            pass
        transport, units = chunks.transport, chunks.time_units or 1_000_000
    if transport is None or len(transport.connections) < least:
        return ()
    # (the first bus reads the whole file: it tells the packets passed over; a later one's offset -1: a pcapng
    # describing an interface after its first packet is read from its start, the blocks before the span passed over)
    seek = 1 if transport.seekable else 0
    return tuple(PacketInterface(ordinal, Interface(LINKTYPE_USER0, 0, units, name=f"{kind} {a} - {b}"),
                                 first=ordinal == 0, connection=(kind, a, b),
                                 span=_span(transport.spans[(kind, a, b)], seek) if ordinal else None)
                 for ordinal, (kind, a, b) in enumerate(transport.connections))


def _span(span: list, seek: int) -> Span:  # type: ignore[type-arg]
    first, last, offset, start, before = span
    return first, last, offset if seek else -1, start, before


def several_interfaces(path: str) -> bool:
    """Do packets of a regular pcapng file come from more than one interface (any link type)? Then each bus's time
    column counts the file's packets, as tshark's (sources/pcapng.py read_pcapng)."""
    try:
        status = os.stat(path)
        return stat.S_ISREG(status.st_mode) and _walked(path, status.st_size, status.st_mtime_ns)[3] > 1
    except (OSError, struct.error, ValueError, SourceError):
        return False


@functools.lru_cache(maxsize=8)
def _walked(path: str, size: int, _mtime: int) -> tuple[tuple[PacketInterface, ...], int, bool, int]:
    """_walk's answer, walked once (each bus asks again as it is opened: 1,600 buses walked a file of 3,200
    packets 3,200 times, quadratic)."""
    with open(path, "rb", buffering=0) as stream:
        buses, described, networked, carrying = _walk(stream, size, path)
        return tuple(buses), described, networked, carrying


def _walk(stream, size: int, path: str) -> tuple[list[PacketInterface], int, bool, int]:  # type: ignore[no-untyped-def]
    """The serial interfaces carrying packets, how many interfaces are described, whether a network one carries
    packets, and how many carry packets. Block by block from a megabyte read at a time (a block header parsed in
    memory, bodies passed over)."""
    if stream.read(4) != SHB_MAGIC:
        return [], 0, False, 0
    described: list[Interface] = []
    section: list[int] = []  # the section's interfaces' ordinals
    used: set[int] = set()
    order = "<"
    buffer, base, position = b"", 0, 0  # buffer holds the file's bytes from `base` on
    while position + 12 <= size:
        if position + 12 > base + len(buffer) or position < base:
            stream.seek(position)
            buffer, base = stream.read(SCAN_BUFFER), position
            if len(buffer) < 12:
                break
        at = position - base
        head = buffer[at : at + 12]
        if head[:4] == SHB_MAGIC:
            order = "<" if head[8:12] == b"\x4d\x3c\x2b\x1a" else ">"
            section = []
        block_type, total = struct.unpack(order + "II", head[:8])
        if total < 12 or total % 4 or position + total > size:
            break
        if block_type == IDB:
            if total - 12 > MAX_HEADER_BLOCK:
                break
            if position + total > base + len(buffer):
                stream.seek(position + 8)
                body = stream.read(total - 12)
                buffer, base = b"", 0
            else:
                body = buffer[at + 8 : at + total - 4]
            section.append(section_ordinal(_interface(body, order, path), described, section))
        elif block_type in (EPB, OPB, SPB):
            if block_type == SPB:
                index = 0
            elif block_type == EPB:
                index = struct.unpack(order + "I", head[8:12])[0]
            else:
                index = struct.unpack(order + "H", head[8:10])[0]
            if index < len(section):
                used.add(section[index])
        position += total
    # (an interface carrying no serial bytes is no bus: the reader passes its packets over, saying so)
    buses = [PacketInterface(ordinal, described[ordinal]) for ordinal in sorted(used)
             if serial(described[ordinal].linktype)]
    if buses:
        buses[0].first = True
    return buses, len(described), any(described[ordinal].linktype in NETWORK_LINKTYPES for ordinal in used), len(used)


def network_chunks(stream, path: str, log: WarningLog, chunk_size: int, ports: RtuPorts,  # type: ignore[no-untyped-def]
                    connection: Connection | None, span: Span | None = None, where: str = ""):
    """The chunks of a pcap or pcapng read for its network link's RTU payloads (`connection`: one's alone);
    their `transport` (sources/ethernet.py): a pcap's from its header, a pcapng's once a network packet is read;
    None for a serial capture."""
    from dissector.sources.compressed import HEADER_BYTES, Decompressed, compression

    kind = compression(stream.read(HEADER_BYTES), path)
    stream.seek(0)
    if kind is not None:  # (a .pcap.gz: read decompressed, as reader.py reads it; before, one stream of all)
        stream = Decompressed(kind, b"", stream, path, log)
    head = stream.read(4)
    inp = Input(stream, path, prefix=head)
    if is_pcap(head):
        return read_pcap(inp, log, chunk_size, ports, connection, span, where)
    return read_pcapng(inp, log, chunk_size, ports=ports, connection=connection, span=span, where=where,
                       networks=True)
