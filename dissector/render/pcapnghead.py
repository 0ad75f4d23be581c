"""The interface a -w file keeps from its input: the name and description of a pcapng's first serial
interface, read from the file's head (as editcap and tshark -w keep a capture's interfaces)."""
from __future__ import annotations

import struct
from collections.abc import Iterator

from dissector.sources.pcapng_blocks import serial

Interface = tuple[str | None, str | None]  # pcapng if_name, if_description


def pcapng_interface(path: str) -> Interface | None:
    """The name and description of a pcapng file's first serial interface, for the -w file to keep (as
    editcap and tshark -w keep a capture's interfaces); None when the file is no pcapng or names none.
    The file's head is hostile data: every length is checked against what was read."""
    try:
        with open(path, "rb") as stream:
            head = stream.read(HEAD_BYTES)
    except OSError:
        return None
    if len(head) < 12 or head[:4] != b"\x0a\x0d\x0d\x0a":
        return None
    order = "<" if head[8:12] == b"\x4d\x3c\x2b\x1a" else ">"
    position = 0
    while position + 12 <= len(head):
        block_type, total = struct.unpack_from(order + "II", head, position)
        if total < 12 or total % 4 or position + total > len(head):
            return None
        linktype = struct.unpack_from(order + "H", head, position + 8)[0]
        if block_type == 1 and not serial(linktype):  # (an Ethernet interface beside the serial one: no bus)
            position += total
            continue
        if block_type == 1:  # IDB: link type, reserved, snaplen, then options
            texts = dict(_text_options(head[position + 16 : position + total - 4], order))
            name, description = texts.get(2), texts.get(3)
            return (name, description) if name or description else None
        if block_type in (6, 3, 2):  # a packet before any interface: nothing to keep
            return None
        position += total
    return None


def _text_options(body: bytes, order: str) -> Iterator[tuple[int, str]]:
    position = 0
    while position + 4 <= len(body):
        code, length = struct.unpack_from(order + "HH", body, position)
        if code == 0 or position + 4 + length > len(body):
            return
        yield code, body[position + 4 : position + 4 + length].decode("utf-8", "replace")
        position += 4 + length + (-length % 4)


HEAD_BYTES = 1 << 20  # the section and first interface blocks are far smaller
