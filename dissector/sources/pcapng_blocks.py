"""pcapng blocks' layouts (pcapng.py reads the file): the block types, the options, an interface's description
(IDB: link type, if_tsresol, if_tsoffset, if_name, if_description)."""
from __future__ import annotations

import struct
from collections.abc import Iterator
from dataclasses import dataclass

from dissector.sources.common import LINKTYPE_RTAC_SERIAL, LINKTYPE_USER0, SourceError

SHB = 0x0A0D0D0A
SHB_MAGIC = bytes.fromhex("0a0d0d0a")
IDB, OPB, SPB, EPB = 1, 2, 3, 6
BYTE_ORDER_MAGIC = 0x1A2B3C4D
# Blocks that carry no packet data: NRB, ISB, systemd journal, DSB, custom (copyable or not).
NO_PACKET_BLOCKS = {4: "name resolution", 5: "interface statistics", 9: "systemd journal",
                    0x0A: "decryption secrets", 0x0BAD: "custom", 0x40000BAD: "custom"}
OPT_END, OPT_COMMENT, OPT_IF_NAME, OPT_IF_DESCRIPTION, OPT_TSRESOL, OPT_TSOFFSET = 0, 1, 2, 3, 9, 14
MAX_HEADER_BLOCK = 1 << 20  # SHB and IDB are parsed whole: a bigger one is corruption


@dataclass(slots=True)
class Interface:
    linktype: int
    snaplen: int
    units: int = 1_000_000  # timestamp units per second (if_tsresol)
    offset: int = 0  # seconds added to every timestamp (if_tsoffset)
    texts: tuple[str, ...] = ()  # if_name and if_description, in the file's order
    name: str | None = None  # if_name
    description: str | None = None  # if_description


def is_pcapng(head: bytes) -> bool:
    return head[:4] == SHB_MAGIC


def _options(body: bytes, order: str) -> Iterator[tuple[int, bytes]]:
    position = 0
    while position + 4 <= len(body):
        code, length = struct.unpack_from(order + "HH", body, position)
        position += 4
        if code == OPT_END:
            return
        yield code, body[position : position + length]
        position += (length + 3) & ~3


def _interface(body: bytes, order: str, name: str) -> Interface:
    if len(body) < 8:
        raise SourceError(f"{name}: interface description block too short ({len(body)} bytes)")
    linktype, _reserved, snaplen = struct.unpack_from(order + "HHI", body)
    interface = Interface(linktype, snaplen)
    for code, value in _options(body[8:], order):
        if code == OPT_TSRESOL and value:
            exponent = value[0] & 0x7F
            interface.units = 2**exponent if value[0] & 0x80 else 10**exponent
        elif code == OPT_TSOFFSET and len(value) == 8:
            interface.offset = struct.unpack(order + "q", value)[0]
        elif code in (OPT_IF_NAME, OPT_IF_DESCRIPTION):
            text = value.decode("utf-8", "replace")
            interface.texts += (text,)
            if code == OPT_IF_NAME:
                interface.name = text
            else:
                interface.description = text
    return interface


def serial(linktype: int) -> bool:
    """Does an interface of this link type carry serial bytes vw3-decode reads (common.check_linktype)?"""
    return linktype in (LINKTYPE_USER0, LINKTYPE_RTAC_SERIAL)


def section_ordinal(interface: Interface, described: list[Interface], section: list[int]) -> int:
    """The file's ordinal of an interface a section describes (`section`: this section's ordinals so far): an
    earlier section's identical interface's (a file of sections cat'ed from one tap is one bus, as tshark 4.0 and
    the plugin read it: before, the answers in the second section were another bus's, `[no request]`), else a new
    one, added to `described`."""
    for ordinal, known in enumerate(described):
        if known == interface and ordinal not in section:
            return ordinal
    described.append(interface)
    return len(described) - 1

