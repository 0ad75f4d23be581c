"""Writing pcapng files: one section, an interface a capture (the serial port), one packet block a record.

Beside what classic pcap holds, the interface says what the port was (`if_name`, and the serial
settings in `if_description`: `/dev/ttyUSB0 19200 8E1`) and each record may carry a comment
(`opt_comment`): vw3-decode comments noise runs, so Wireshark's packet list says why bytes are not a
frame. Timestamps are in microseconds (the default if_tsresol), as the classic pcap writer's, or in
nanoseconds (if_tsresol 9) for a copy of a nanosecond capture; an interface copied from a pcapng keeps
its if_tsresol (10^-3 s, 2^-10 s), as editcap and tshark -w keep it.
Each block is written (and flushed) in one write, so the file is valid at any instant.
"""
from __future__ import annotations

import struct
from typing import BinaryIO

from dissector.render.pcapwriter import LINKTYPE_USER0, MICROS, SNAPLEN, clamp_time, split_time

SHB, IDB, EPB = 0x0A0D0D0A, 0x00000001, 0x00000006
BYTE_ORDER_MAGIC = 0x1A2B3C4D
OPT_ENDOFOPT, OPT_COMMENT = 0, 1
SHB_USERAPPL = 4
IF_NAME, IF_DESCRIPTION, IF_TSRESOL = 2, 3, 9
TICKS = 1 << 64  # an EPB's 64-bit time: of microseconds up to the year 586,912; of nanoseconds 2554


def tsresol(units: int) -> int | None:
    """The if_tsresol byte of `units` a second (10^n: n, 2^n: 0x80 | n), None for microseconds (the
    default) or units no if_tsresol says (or whose ticks never reach a second: more than 2^64 a second)."""
    if units == MICROS or units > TICKS:
        return None
    text = str(units)
    if text == "1" + "0" * (len(text) - 1):
        return len(text) - 1
    return 0x80 | units.bit_length() - 1 if units & (units - 1) == 0 else None


def resolution_text(units: int) -> str:
    """`10^-3 s`, `2^-10 s`: an if_tsresol as a message names it."""
    byte = tsresol(units)
    if byte is None:
        return "10^-6 s" if units == MICROS else f"1/{units} s"
    return f"2^-{byte & 0x7F} s" if byte & 0x80 else f"10^-{byte} s" if byte else "1 s"


def _option(code: int, value: bytes) -> bytes:
    return struct.pack("<HH", code, len(value)) + value + b"\0" * (-len(value) % 4)


def _options(options: list[tuple[int, str | bytes]]) -> bytes:
    if not options:
        return b""
    return b"".join(_option(code, value if isinstance(value, bytes) else value.encode("utf-8"))
                    for code, value in options) + _option(OPT_ENDOFOPT, b"")


def _block(block_type: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", block_type, total) + body + struct.pack("<I", total)


class PcapngWriter:
    def __init__(
        self,
        stream: BinaryIO,
        linktype: int = LINKTYPE_USER0,
        flush: bool = True,
        if_name: str | None = None,
        if_description: str | None = None,
        application: str = "vw3-decode",
        units: int = MICROS,
        if_units: int | None = None,
    ) -> None:
        """`units`: MICROS, or NANOS (an interface's if_tsresol 9) of interfaces given none; `if_units`: the
        first interface's own (a copied pcapng interface's if_tsresol)."""
        self._stream = stream
        self._flush = flush
        self._units = units
        section = struct.pack("<IHHq", BYTE_ORDER_MAGIC, 1, 0, -1) + _options([(SHB_USERAPPL, application)])
        self._linktype = linktype
        # The interfaces described so far, in order (an EPB names its interface by this index), with units.
        first = (if_name, if_description, self._own(if_units))
        self._interfaces: list[tuple[str | None, str | None, int]] = [first]
        self._interface = 0
        head = _block(SHB, section) + self._interface_block(*first)
        self.size = len(head)
        self.clamped = 0  # records whose time was before 1970 or past 64 bits of microseconds
        stream.write(head)
        if flush:
            stream.flush()

    def _own(self, units: int | None) -> int:
        """An interface's units: its own where an if_tsresol says them, else the file's."""
        return units if units is not None and (units == MICROS or tsresol(units) is not None) else self._units

    def _interface_block(self, name: str | None, description: str | None, units: int) -> bytes:
        options: list[tuple[int, str | bytes]] = [(IF_NAME, name)] if name else []
        if description:
            options.append((IF_DESCRIPTION, description))
        resolution = tsresol(units)
        if resolution is not None:
            options.append((IF_TSRESOL, bytes([resolution])))
        return _block(IDB, struct.pack("<HHI", self._linktype, 0, SNAPLEN) + _options(options))

    def use_interface(self, name: str | None, description: str | None, units: int | None = None) -> None:
        """The next records' interface: a new interface block unless the file describes it already
        (one decode of several captures keeps each capture's interface, as mergecap does); `units`: its
        own (the input interface's if_tsresol), else the file's."""
        key = (name, description, self._own(units))
        if key in self._interfaces:
            self._interface = self._interfaces.index(key)
            return
        block = self._interface_block(*key)
        self._stream.write(block)
        self.size += len(block)
        self._interfaces.append(key)
        self._interface = len(self._interfaces) - 1
        if self._flush:
            self._stream.flush()

    def write(self, data: bytes, timestamp: float | None = None, comment: str | list[str] | None = None,
              original: int | None = None) -> None:
        """`comment`: a list is an opt_comment each (the input's packet comments, then vw3-decode's); `original`:
        the record's length on the line when only part of it was captured (pcapwriter.PcapWriter.write)."""
        comments = [comment] if isinstance(comment, str) else comment or []
        if timestamp is None:  # (untimed: at the epoch, as the readers take it back: sources/pcap.py EpochRecord)
            timestamp = 0.0
        per_second = self._interfaces[self._interface][2]
        seconds, fraction, moved = clamp_time(*split_time(timestamp, per_second), TICKS // per_second - 1,
                                              per_second)
        self.clamped += moved
        units = seconds * per_second + fraction
        body = (
            struct.pack("<IIIII", self._interface, units >> 32, units & 0xFFFFFFFF, len(data),
                        len(data) if original is None else max(original, len(data)))
            + data
            + b"\0" * (-len(data) % 4)
            + _options([(OPT_COMMENT, text) for text in comments if text])
        )
        block = _block(EPB, body)
        self._stream.write(block)
        self.size += len(block)
        if self._flush:
            self._stream.flush()

    def close(self) -> None:
        self._stream.close()
