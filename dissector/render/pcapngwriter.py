"""Writing pcapng files: one section, an interface a capture (the serial port), one packet block a record.

Beside what classic pcap holds, the interface says what the port was (`if_name`, and the serial
settings in `if_description`: `/dev/ttyUSB0 19200 8E1`) and each record may carry a comment
(`opt_comment`): vw3-decode comments noise runs, so Wireshark's packet list says why bytes are not a
frame. Timestamps are in microseconds (the default if_tsresol), as the classic pcap writer's, or in
nanoseconds (if_tsresol 9) for a copy of a nanosecond capture.
Each block is written (and flushed) in one write, so the file is valid at any instant.
"""
from __future__ import annotations

import struct
from typing import BinaryIO

from dissector.render.pcapwriter import LINKTYPE_USER0, MICROS, NANOS, SNAPLEN, clamp_time, split_time

SHB, IDB, EPB = 0x0A0D0D0A, 0x00000001, 0x00000006
BYTE_ORDER_MAGIC = 0x1A2B3C4D
OPT_ENDOFOPT, OPT_COMMENT = 0, 1
SHB_USERAPPL = 4
IF_NAME, IF_DESCRIPTION, IF_TSRESOL = 2, 3, 9
# 64 bits of microseconds: up to the year 586,912; of nanoseconds: 2554.
SECONDS_MAX = {MICROS: (1 << 64) // MICROS - 1, NANOS: (1 << 64) // NANOS - 1}


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
    ) -> None:
        """`units`: MICROS, or NANOS (every interface's if_tsresol 9)."""
        self._stream = stream
        self._flush = flush
        self._units = units
        section = struct.pack("<IHHq", BYTE_ORDER_MAGIC, 1, 0, -1) + _options([(SHB_USERAPPL, application)])
        self._linktype = linktype
        # The interfaces described so far, in order (an EPB names its interface by this index).
        self._interfaces: list[tuple[str | None, str | None]] = [(if_name, if_description)]
        self._interface = 0
        head = _block(SHB, section) + self._interface_block(if_name, if_description)
        self.size = len(head)
        self.clamped = 0  # records whose time was before 1970 or past 64 bits of microseconds
        stream.write(head)
        if flush:
            stream.flush()

    def _interface_block(self, name: str | None, description: str | None) -> bytes:
        options: list[tuple[int, str | bytes]] = [(IF_NAME, name)] if name else []
        if description:
            options.append((IF_DESCRIPTION, description))
        if self._units == NANOS:
            options.append((IF_TSRESOL, bytes([9])))
        return _block(IDB, struct.pack("<HHI", self._linktype, 0, SNAPLEN) + _options(options))

    def use_interface(self, name: str | None, description: str | None) -> None:
        """The next records' interface: a new interface block unless the file describes it already
        (one decode of several captures keeps each capture's interface, as mergecap does)."""
        key = (name, description)
        if key in self._interfaces:
            self._interface = self._interfaces.index(key)
            return
        block = self._interface_block(name, description)
        self._stream.write(block)
        self.size += len(block)
        self._interfaces.append(key)
        self._interface = len(self._interfaces) - 1
        if self._flush:
            self._stream.flush()

    def write(self, data: bytes, timestamp: float | None = None, comment: str | list[str] | None = None) -> None:
        """`comment`: a list is an opt_comment each (the input's packet comments, then vw3-decode's)."""
        comments = [comment] if isinstance(comment, str) else comment or []
        if timestamp is None:  # (untimed: at the epoch, as the readers take it back: sources/pcap.py EpochRecord)
            timestamp = 0.0
        per_second = self._units
        seconds, fraction, moved = clamp_time(*split_time(timestamp, per_second), SECONDS_MAX[per_second],
                                              per_second)
        self.clamped += moved
        units = seconds * per_second + fraction
        body = (
            struct.pack("<IIIII", self._interface, units >> 32, units & 0xFFFFFFFF, len(data), len(data))
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
