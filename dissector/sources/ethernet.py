"""Modbus RTU carried over TCP or UDP by a serial gateway, read from the pcap/pcapng records of a network
link (Ethernet, Linux cooked SLL/SLL2, raw IP, BSD loopback): the payloads on the RTU ports are the bus's
bytes, each packet a record with its time, as the plugin reads them (lua/src/dissector.lua: its tcp_port and
udp_port preferences, 0 by default: none). Each TCP connection or UDP conversation is a stream of its own,
both directions in capture order (a request, its answer), its segments its records: a frame split over two
segments waits in the stream for its end, as on a serial capture (no TCP reassembly, as the plugin).

Packets with no bytes for the bus (ARP, other ports, TCP without payload) are counted and told in one
warning; a capture with none on the ports is refused in one line naming the ports, the options and the ports
that did carry payloads (Modbus/TCP on 502 named as such: vw3-decode reads its serial form only).
"""
from __future__ import annotations

import struct
from bisect import bisect_right
from dataclasses import dataclass, field

from dissector.errors import SourceError
from dissector.protocol.crc import crc16_reference

LINKTYPE_NULL, LINKTYPE_ETHERNET, LINKTYPE_RAW, LINKTYPE_LINUX_SLL = 0, 1, 101, 113
LINKTYPE_IPV4, LINKTYPE_IPV6, LINKTYPE_LINUX_SLL2 = 228, 229, 276
NETWORK_LINKTYPES = frozenset({LINKTYPE_NULL, LINKTYPE_ETHERNET, LINKTYPE_RAW, LINKTYPE_LINUX_SLL,
                               LINKTYPE_IPV4, LINKTYPE_IPV6, LINKTYPE_LINUX_SLL2})
ETHERTYPE_IPV4, ETHERTYPE_IPV6 = 0x0800, 0x86DD
VLAN_TAGS = (0x8100, 0x88A8, 0x9100)  # 802.1Q, 802.1ad (QinQ) and the older QinQ tag: 4 bytes each
TCP, UDP = 6, 17
# IPv6 extension headers before the transport's, as Wireshark's IPv6 walks them: hop-by-hop, routing, destination
# options (8-byte units after the first 8) and AH (4-byte units after the first 8); the fragment header's 8 bytes.
IPV6_OPTIONS, IPV6_AH, IPV6_FRAGMENT = frozenset({0, 43, 60}), 51, 44
MODBUS_TCP_PORT = 502  # Modbus/TCP (MBAP header, no CRC): its own protocol, not the bus's bytes
OPTIONS = "--tcp-port and --udp-port, as the plugin's vw3.tcp_port and vw3.udp_port preferences,"
TCP_NAME = "TCP"
LINK_NAMES = {LINKTYPE_NULL: "BSD loopback", LINKTYPE_ETHERNET: "Ethernet", LINKTYPE_RAW: "raw IP",
              LINKTYPE_LINUX_SLL: "Linux cooked", LINKTYPE_IPV4: "IPv4", LINKTYPE_IPV6: "IPv6",
              LINKTYPE_LINUX_SLL2: "Linux cooked v2"}


@dataclass(frozen=True, slots=True)
class RtuPorts:
    """The TCP and UDP ports whose payloads are Modbus RTU (0: none), as the plugin's preferences."""

    tcp: int = 0
    udp: int = 0

    def text(self) -> str:
        given = [f"{name} port {port}" for name, port in (("TCP", self.tcp), ("UDP", self.udp)) if port]
        return " and ".join(given) if given else "none given"


Connection = tuple[str, str, str]  # (transport, one end, the other end): the same both ways
# A connection's first and last record numbers, the file offset of its first's data, the capture's first packet's
# time and the time of the packet before its first (ns; None: untimed): PacketTimes' start for a bus read alone.
Span = tuple[int, int, int, "int | None", "int | None"]


@dataclass(slots=True)
class Segment:
    """A packet's transport payload: its connection, its bytes, the length its headers declare (more than
    the bytes when the record was captured in part)."""

    connection: Connection
    ports: tuple[int, int]  # (source, destination)
    transport: str
    data: bytes
    declared: int
    sender: str = ""  # its source end
    seq: int | None = None  # TCP's sequence number
    syn: bool = False  # a TCP SYN: a connection (re)starts, its sequence numbers anew
    ack: int = 0  # TCP's acknowledgment number, window and flags (duplicate ACKs: Transport._acks)
    window: int = 0
    flags: int = 0


def _address(raw: bytes) -> str:
    if len(raw) == 4:
        return ".".join(map(str, raw))
    return ":".join(raw[index : index + 2].hex() for index in range(0, 16, 2))


def _ip(packet: bytes) -> tuple[int, bytes, bytes, bytes, int] | str:
    """(protocol, source, destination, IP payload, its declared length) of an IPv4/IPv6 packet, or why not."""
    if not packet:
        return "not IP"
    version = packet[0] >> 4
    if version == 4 and len(packet) >= 20:
        header = (packet[0] & 0x0F) * 4
        total, flags_offset, protocol = struct.unpack_from("!H2xHxB", packet, 2)
        total = total or len(packet)  # (0: a segment the sender's NIC splits, TSO, captured before: Wireshark's guess)
        if flags_offset & 0x3FFF:  # (more fragments, or a fragment's offset: no transport header of its own)
            return "fragmented IP"
        return protocol, packet[12:16], packet[16:20], packet[header:total], total - header
    if version == 6 and len(packet) >= 40:
        chain = _ipv6_chain(packet)
        if isinstance(chain, str):
            return chain
        protocol, at, end, fragment = chain
        if fragment is not None and struct.unpack_from("!H", packet, fragment + 2)[0] & 0xFFF9:
            return "fragmented IP"  # (an offset or more fragments; an atomic fragment, neither, is the datagram)
        return protocol, packet[8:24], packet[24:40], packet[at:end], max(end - at, 0)
    return "not IP"


def _ipv6_chain(packet: bytes) -> tuple[int, int, int, int | None] | str:
    """(the transport's protocol, where its header starts, where the payload ends, where the fragment header is
    or None) of an IPv6 packet, past its extension headers; or why not."""
    length, protocol = struct.unpack_from("!HB", packet, 4)
    at, end, fragment = 40, 40 + length, None
    while protocol in IPV6_OPTIONS or protocol in (IPV6_AH, IPV6_FRAGMENT):
        if len(packet) < at + 8:
            return "IPv6 extension headers captured in part"
        if protocol == IPV6_FRAGMENT:
            fragment, size = at, 8
        else:
            size = (packet[at + 1] + 2) * 4 if protocol == IPV6_AH else (packet[at + 1] + 1) * 8
        protocol, at = packet[at], at + size
    return protocol, at, end, fragment


def network_payload(linktype: int, record: bytes) -> bytes | str:
    """The IP packet a record of a network link carries, or why none (ARP, ...)."""
    if linktype == LINKTYPE_ETHERNET:
        at, ethertype = 12, None
        while len(record) >= at + 2:
            ethertype = struct.unpack_from("!H", record, at)[0]
            if ethertype not in VLAN_TAGS:
                break
            at += 4
        start = at + 2
    elif linktype == LINKTYPE_LINUX_SLL:
        ethertype = struct.unpack_from("!H", record, 14)[0] if len(record) >= 16 else None
        start = 16
    elif linktype == LINKTYPE_LINUX_SLL2:
        ethertype = struct.unpack_from("!H", record, 0)[0] if len(record) >= 20 else None
        start = 20
    elif linktype == LINKTYPE_NULL:  # (the address family in the writer's byte order: 2 IPv4, 24/28/30 IPv6)
        family = int.from_bytes(record[:4], "little") if len(record) >= 4 else -1
        family = family if family < 0x10000 else int.from_bytes(record[:4], "big")
        ethertype = ETHERTYPE_IPV4 if family == 2 else ETHERTYPE_IPV6 if family in (24, 28, 30) else None
        start = 4
    else:  # raw IP
        return record
    if ethertype not in (ETHERTYPE_IPV4, ETHERTYPE_IPV6):
        return "not IP"
    return record[start:]


def segment(linktype: int, record: bytes) -> Segment | str:
    """The TCP or UDP payload of a record of a network link, or why it has none."""
    packet = network_payload(linktype, record)
    if isinstance(packet, str):
        return packet
    ip = _ip(packet)
    if isinstance(ip, str):
        return ip
    protocol, source, destination, body, declared = ip
    seq = None
    if protocol == TCP and len(body) >= 20:
        sport, dport, seq, ack, offset, flags, window = struct.unpack_from("!HHIIBBH", body)
        header, name = (offset >> 4) * 4, "TCP"
    elif protocol == UDP and len(body) >= 8:
        sport, dport, length = struct.unpack_from("!HHH", body)
        header, name, declared, flags, ack, window = 8, "UDP", length, 0, 0, 0
    else:
        return "not TCP or UDP"
    a, b = f"{_address(source)}:{sport}", f"{_address(destination)}:{dport}"
    connection = (name, *sorted((a, b)))
    return Segment(connection, (sport, dport), name, body[header:declared], max(declared - header, 0), a, seq,
                   bool(flags & 0x02), ack, window, flags)


# PacketTimes' marks kept at most, whoever asks (memory bounded: ~40 MB): the newest 3/4 are more than the framing
# engine's block of 256 kB can hold (a mark a byte at least: accel/records.py BLOCK_BYTES), the ones it may ask.
UNASKED_MARKS = 1 << 19


class PacketTimes:
    """What tshark's time columns count from on a network capture (or a several-interface pcapng: its serial buses,
    sources/pcapng.py read_pcapng `shared`), whose packets without bus bytes are no items
    (render/timefmt.py Clock): `start`, its first packet's time (frame.time_relative's zero, any packet, any
    connection's or interface's), and for each of the bus's packets, by the stream offset of its first byte,
    the time of the packet captured before it (frame.time_delta's reference). ns; None: untimed."""

    def __init__(self, start: int | None = None, last: int | None = None) -> None:
        self.start, self.last = start, last  # (last: the last packet's read, the next one's reference)
        self.fed = 0  # the bus's bytes so far
        self.offsets: list[int] = []
        self.befores: list[int | None] = []

    def packet(self, ns: int | None) -> int | None:
        """A packet read at `ns`, the bus's or not: the time of the one before it."""
        before = self.last
        if ns is not None:
            self.start = ns if self.start is None else self.start
            self.last = ns
        return before

    def taken(self, length: int, before: int | None) -> None:
        """The bus's next `length` bytes came in a packet captured after one at `before`."""
        if len(self.offsets) >= UNASKED_MARKS:  # (--stats counted in the engine asks none, nor calls forget)
            del self.offsets[: UNASKED_MARKS // 4], self.befores[: UNASKED_MARKS // 4]
        self.offsets.append(self.fed)
        self.befores.append(before)
        self.fed += length

    def before(self, offset: int) -> int | None:
        """The time of the packet before the one holding the bus's byte at `offset`."""
        index = bisect_right(self.offsets, offset) - 1
        return self.befores[index] if index >= 0 else None

    def forget(self, offset: int) -> None:
        """Items before `offset` are done with (memory stays bounded: the marks read ahead of the framer)."""
        index = bisect_right(self.offsets, offset) - 1
        if index > 4096:
            del self.offsets[:index], self.befores[:index]


MAX_DATAGRAMS = 64  # IP datagrams awaiting fragments at once (the oldest dropped): memory bounded, ~8 MB


@dataclass(slots=True)
class _Datagram:
    """An IP datagram's fragments so far: its bytes and which 8-byte blocks of them came."""

    header: bytes = b""  # the first fragment's IP header
    data: bytearray = field(default_factory=bytearray)
    have: bytearray = field(default_factory=bytearray)  # one byte per 8-byte block: 1 when it came
    blocks: int = 0  # blocks that came
    total: int | None = None  # its length, once the last fragment (no more fragments) came
    count: int = 0  # fragments taken


class Fragments:
    """IPv4 and IPv6 reassembly, as Wireshark's ip.defragment and ipv6.defragment (on by default): a fragmented datagram's transport
    payload is read in the packet of its last fragment to come, as the plugin is given it. A fragment's cost
    is its length; at most MAX_DATAGRAMS wait, the oldest given up (counted)."""

    def __init__(self) -> None:
        self.waiting: dict[tuple[bytes, bytes, int, int], _Datagram] = {}
        self.given_up = 0  # fragments of datagrams never completed

    def add(self, packet: bytes) -> bytes | None:
        """The whole IP packet once `packet`, a fragment, completes it; else None. An IPv6 datagram is given back
        with its 40-byte header alone before its transport's (its extension headers read)."""
        if packet[:1] and packet[0] >> 4 == 6:
            chain = _ipv6_chain(packet)
            if isinstance(chain, str):
                self.given_up += 1
                return None
            _protocol, at, end, at_fragment = chain
            if at_fragment is None:  # (not reached: _ip said "fragmented IP")
                return None
            offset_flags, ident = struct.unpack_from("!HI", packet, at_fragment + 2)
            start, more = offset_flags & 0xFFF8, bool(offset_flags & 1)
            key = (packet[8:24], packet[24:40], ident, 6)
            head = packet[:6] + bytes([packet[at_fragment]]) + packet[7:40]  # (its next header the fragment's)
            return self._piece(key, start, more, packet[at:end], head)
        if len(packet) < 20:
            self.given_up += 1
            return None
        header = (packet[0] & 0x0F) * 4
        total, ident, flags_offset, protocol = struct.unpack_from("!HHHxB", packet, 2)
        start, more = (flags_offset & 0x1FFF) * 8, bool(flags_offset & 0x2000)
        return self._piece((packet[12:16], packet[16:20], ident, protocol), start, more,
                           packet[header:total or len(packet)], packet[:header])

    def _piece(self, key: tuple[bytes, bytes, int, int], start: int, more: bool, piece: bytes, header: bytes
               ) -> bytes | None:
        """A fragment's `piece` of the datagram `key` from byte `start` (`header`: its packet's IP header)."""
        datagram = self.waiting.pop(key, None) or _Datagram()
        self.waiting[key] = datagram  # (the most recent last: the first is the oldest)
        if len(self.waiting) > MAX_DATAGRAMS:
            self.given_up += self.waiting.pop(next(iter(self.waiting))).count
        end = min(start + len(piece), 0xFFFF)
        if start >= end:
            datagram.count += 1
            return None
        if not more:
            datagram.total = end
        if start == 0:
            datagram.header = header
        if len(datagram.data) < end:
            datagram.data.extend(bytes(end - len(datagram.data)))
            datagram.have.extend(bytes(-(-end // 8) - len(datagram.have)))
        datagram.data[start:end] = piece[: end - start]
        for block in range(start // 8, -(-end // 8)):
            datagram.blocks += not datagram.have[block]
            datagram.have[block] = 1
        datagram.count += 1
        if datagram.total is None or not datagram.header or datagram.blocks < -(-datagram.total // 8):
            return None
        del self.waiting[key]
        head, data = datagram.header, bytes(datagram.data[: datagram.total])
        if head[0] >> 4 == 6:
            return head[:4] + struct.pack("!H", datagram.total) + head[6:40] + data
        return head[:2] + struct.pack("!H4x", len(head) + datagram.total) + head[8:] + data

    def finish(self) -> int:
        """The fragments of datagrams never completed, all told."""
        self.given_up += sum(datagram.count for datagram in self.waiting.values())
        self.waiting.clear()
        return self.given_up


@dataclass(slots=True)
class Transport:
    """The reading of one capture's network records: which payloads are the bus's (`only`: one connection's,
    when each is read as its own bus), and what the others were, for the end's warning or refusal."""

    name: str
    ports: RtuPorts
    only: Connection | None = None
    linktype: int | None = None  # the first record's
    taken: int = 0
    skipped: dict[str, int] = field(default_factory=dict)
    elsewhere: dict[tuple[str, int], int] = field(default_factory=dict)  # payloads on other ports
    connections: list[Connection] = field(default_factory=list)  # on the RTU ports, in order of appearance
    # Each one's Span (`seen`, a dict: a capture of thousands of connections, one per poll, looked each packet's
    # up in the list); `span`: the one read's, whose records alone are parsed, the others passed over unread
    # (a file is read once per connection: 1,600 connections of one poll each took 417 s, cubic).
    spans: dict[Connection, list[int]] = field(default_factory=dict)
    span: Span | None = None
    block: int | None = None  # a pcapng's: the file offset of the packet block read, a span's offset
    seekable: bool = True  # a pcapng's: no interface described after its first packet (a span may be sought)
    times: PacketTimes = field(default_factory=PacketTimes)
    fragments: Fragments = field(default_factory=Fragments)
    judged: set[Connection] = field(default_factory=set)  # connections whose first payload was looked at
    sent: dict[tuple[Connection, str], int] = field(default_factory=dict)  # a TCP sender's next sequence number
    # A TCP sender's acknowledgments, as Wireshark's analysis keeps them: [last ack, its time (ns), duplicate
    # ACKs since, window, next sequence number of any segment]
    acks: dict[tuple[Connection, str], list] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.span is not None:  # (read from its first record: the capture's start and the packet before told)
            self.times = PacketTimes(self.span[3], self.span[4])

    def outside(self, number: int) -> bool:
        """Record `number` is outside the span of the one connection read: not the bus's, unparsed."""
        return self.span is not None and not self.span[0] <= number <= self.span[1]

    def past(self, number: int) -> bool:
        """Record `number` is the last of the one connection read, or after it: the reading can end."""
        return self.span is not None and number >= self.span[1]

    def take(self, linktype: int, record: bytes, number: int, offset: int = 0, now: int | None = None
             ) -> Segment | None:
        """The payload of record `number` (its data at `offset` in the file) when it is the bus's; else None
        (counted)."""
        self.linktype = linktype if self.linktype is None else self.linktype
        before = self.times.packet(now)
        found = segment(linktype, record)
        if found == "fragmented IP":  # (read whole in its last fragment's packet, as Wireshark's IP gives it)
            packet = self.fragments.add(network_payload(linktype, record))  # type: ignore[arg-type]
            if packet is None:
                return None
            found = segment(LINKTYPE_RAW, packet)
        if isinstance(found, str):
            return self._skip(found)
        port = self.ports.tcp if found.transport == "TCP" else self.ports.udp
        if not port or port not in found.ports:
            if found.declared:  # (the server's port, as a user sets it: the lower, an ephemeral one is high)
                key = (found.transport, min(found.ports))
                self.elsewhere[key] = self.elsewhere.get(key, 0) + 1
            return self._skip("other ports" if found.declared else f"{found.transport} without payload")
        span = self.spans.get(found.connection)
        if span is None:
            self.connections.append(found.connection)
            at = offset if self.block is None else self.block
            self.spans[found.connection] = [number, number, at, self.times.start, before]
        else:
            span[1] = number
        if self.only is not None and found.connection != self.only:
            return self._skip("other connections")
        if found.syn:  # (its ports used again, its sequence numbers new: Wireshark's "port numbers reused")
            for end in found.connection[1:]:
                self.sent.pop((found.connection, end), None)
                self.acks.pop((found.connection, end), None)
        if found.seq is not None:
            self._acks(found, now)
        if not found.declared:
            return self._skip(f"{found.transport} without payload")
        if found.seq is not None and self._again(found, now):
            return self._skip("TCP retransmissions")
        if found.connection not in self.judged:  # (its first payload)
            self.judged.add(found.connection)
            self._refuse_modbus_tcp(found, port, number)
        self.taken += 1
        self.times.taken(len(found.data), before)
        return found

    def _refuse_modbus_tcp(self, found: Segment, port: int, number: int) -> None:
        """A connection whose first payload is a Modbus/TCP ADU (MBAP header: protocol 0, its length the
        rest), not an RTU frame (its CRC): refused in one line rather than shown as noise."""
        data = found.data
        if len(data) < 8 or data[2:4] != b"\0\0" or int.from_bytes(data[4:6], "big") != len(data) - 6:
            return
        if crc16_reference(data[:-2]) == int.from_bytes(data[-2:], "little"):
            return
        raise SourceError(
            f"{self.name}: record {number}: {found.transport} port {port} carries Modbus/TCP (MBAP header: "
            f"transaction {int.from_bytes(data[:2], 'big')}, unit {data[6]}, no CRC), not Modbus RTU frames, "
            "which vw3-decode does not read: tshark with lua/vw3.lua and lua/vw3_modbus.lua names its registers")

    def _acks(self, found: Segment, now: int | None) -> None:
        """Count the sender's duplicate ACKs as Wireshark does (no payload, its window, sequence number and
        acknowledgment the same as before, no SYN, FIN or RST): two of them make the other end's resend of that
        byte a fast retransmission, which Wireshark's TCP does give its subdissector."""
        state = self.acks.setdefault((found.connection, found.sender), [None, None, 0, None, None])
        duplicate = (not found.declared and found.window and found.window == state[3] and found.seq == state[4]
                     and found.ack == state[0] and not found.flags & 0x07)
        state[2] = state[2] + 1 if duplicate else 0
        if found.ack != state[0]:
            state[0], state[1] = found.ack, now
        state[3] = found.window
        end = (found.seq + found.declared + (found.flags & 0x03 != 0)) & 0xFFFFFFFF  # (SYN and FIN count one)
        if state[4] is None or not (end - state[4]) & 0x80000000:
            state[4] = end

    def _fast(self, found: Segment, now: int | None) -> bool:
        """A resend after two duplicate ACKs of its first byte within 20 ms (Wireshark's fast retransmission)."""
        other = found.connection[2] if found.sender == found.connection[1] else found.connection[1]
        state = self.acks.get((found.connection, other))
        return (state is not None and state[2] >= 2 and state[0] == found.seq and now is not None
                and state[1] is not None and now - state[1] < 20_000_000)

    def _again(self, found: Segment, now: int | None = None) -> bool:
        """A TCP segment whose bytes all came before (a retransmission): Wireshark's TCP gives it no
        subdissector, so the plugin never sees it. Sequence numbers compared modulo 2**32."""
        end = (found.seq + found.declared) & 0xFFFFFFFF
        sender = (found.connection, found.sender)  # (a server's end is every connection's)
        sent = self.sent.get(sender)
        if sent is None:
            self.sent[sender] = end
            return False
        if not (end - sent) & 0x80000000:  # (the highest seen, as Wireshark's nextseq: retransmissions too)
            self.sent[sender] = end
        # Wireshark's TCP (tcp.no_subdissector_on_error, on by default) gives no subdissector a segment that
        # starts before the highest sequence number seen (a retransmission or one out of order), even when it
        # brings new bytes after them: an overlapping one was taken whole, its bytes read twice.
        behind = (sent - found.seq) & 0xFFFFFFFF
        return 0 < behind < 0x80000000 and not self._fast(found, now)

    def _skip(self, why: str) -> None:
        self.skipped[why] = self.skipped.get(why, 0) + 1
        return None

    def finish(self, warn) -> None:  # type: ignore[no-untyped-def]
        """At the end: refuse a capture none of whose packets carried the bus's bytes; else tell the
        packets passed over, in one warning (`warn(kind, message)`)."""
        if self.fragments.finish():
            self.skipped["fragmented IP never reassembled"] = self.fragments.given_up
        if not self.taken and self.only is None:
            raise SourceError(self.refusal())
        if self.span is not None:  # (a later connection's bus, read over its span: the first bus tells)
            return
        passed = sum(count for why, count in self.skipped.items() if why != "other connections")
        if passed and (self.only is None or self.connections[:1] == [self.only]):
            said = ", ".join(f"{count} {why}" for why, count in self.skipped.items() if why != "other connections")
            packets = f"{passed} packet carried" if passed == 1 else f"{passed} packets carried"
            warn("skipped packets", f"{self.name}: {packets} no Modbus RTU bytes on {self.ports.text()}: "
                 f"skipped ({said})")

    def refusal(self) -> str:
        """One line: no payload on the RTU ports; the ports that carried some, Modbus/TCP's named."""
        seen = sorted(self.elsewhere.items(), key=lambda item: (-item[1], item[0]))
        shown = ", ".join(f"{transport} port {port} ({count} packet{'s' if count != 1 else ''})"
                          for (transport, port), count in seen[:4])
        label = LINK_NAMES.get(self.linktype or 0, "network link")
        text = (f"{self.name}: {label} (linktype {self.linktype}): no TCP or UDP payload on the Modbus RTU ports "
                f"({self.ports.text()}: {OPTIONS} set them)")
        if shown:
            text += f"; payloads on {shown}{' and more' if len(seen) > 4 else ''}"
        else:
            count = sum(self.skipped.values())
            said = ", ".join(f"{number} {why}" for why, number in self.skipped.items())
            text += f"; its {count} packet{'s' if count != 1 else ''}: {said}"
        if (TCP_NAME, MODBUS_TCP_PORT) in self.elsewhere:
            text += ("; port 502 is Modbus/TCP (MBAP header, no CRC), which vw3-decode does not read: "
                     "tshark with lua/vw3.lua and lua/vw3_modbus.lua names its registers")
        return text
