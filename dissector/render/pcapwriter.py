"""Writing classic pcap files, one Modbus frame (or noise run) a record (a decode's noise run may share the
record of a damaged frame after it, or of the item before it: capturefile.CaptureOutput.write_items).

Every record is written and flushed whole, header first, so a reader that opens the file while it is
being written sees only complete records, and a crash loses nothing already written.
"""
from __future__ import annotations

import struct
from typing import BinaryIO

LINKTYPE_USER0 = 147
LINKTYPE_RTAC_SERIAL = 250
SNAPLEN = 65535

_GLOBAL_HEADER = struct.Struct("<IHHiIII")
_RECORD_HEADER = struct.Struct("<IIII")
PCAP_MAGIC = 0xA1B2C3D4
PCAP_MAGIC_NANO = 0xA1B23C4D  # times in nanoseconds (libpcap's, as tshark -w keeps a nanosecond capture's)
MICROS, NANOS = 1_000_000, 1_000_000_000  # a format's time units per second


def finer_than_micros(units: int) -> bool:
    """Can microseconds not hold times in 1/`units` s (a nanosecond pcap, if_tsresol 10^-7 or 2^-10)?"""
    return units > MICROS or MICROS % units != 0


def split_time(timestamp: float, units: int = MICROS) -> tuple[int, int]:
    """(seconds, fraction in 1/`units` s) as pcap and pcapng store them; the reader's seconds + fraction /
    units gives it back (a pcapng's units: any if_tsresol, 2^-10 s or 10^-3 s as microseconds)."""
    ns = getattr(timestamp, "ns", None)  # a Stamp keeps its source's integer nanoseconds
    if ns is not None:
        if NANOS % units == 0:
            return divmod(int(ns) // (NANOS // units), units)  # type: ignore[return-value]
        # 2^-10 s (or finer than ns): the tick the reader cut these nanoseconds from (Stamp.from_parts), the
        # one whose cut gives them back (editcap's cut writes 166 of 167/1024 s: .163085937 read back .162109375)
        return divmod(-(-int(ns) * units // NANOS), units)  # type: ignore[return-value]
    seconds = int(timestamp)
    fraction = int(round((timestamp - seconds) * units))
    if fraction >= units:
        seconds, fraction = seconds + 1, fraction - units
    return seconds, fraction


PCAP_SECONDS_MAX = 0xFFFFFFFF  # classic pcap's u32 seconds: 1970-01-01 .. 2106-02-07


def clamp_time(seconds: int, micros: int, most: int, units: int = MICROS) -> tuple[int, int, bool]:
    """(seconds, micros) within 0 .. `most` seconds (and its last 1/`units` s), and whether it moved.

    A capture's stamps are data (a pcapng if_tsoffset of -2^62, 2^64 units): a record keeps its bytes
    at the nearest time the format can hold rather than failing half written."""
    if seconds < 0:
        return 0, 0, True
    if seconds > most:
        return most, units - 1, True
    return seconds, micros, False


class PcapWriter:
    def __init__(self, stream: BinaryIO, linktype: int = LINKTYPE_USER0, flush: bool = True,
                 units: int = MICROS) -> None:
        """`units`: MICROS, or NANOS for a nanosecond pcap."""
        self._stream = stream
        self._flush = flush
        self._units = units
        self.size = _GLOBAL_HEADER.size  # bytes written so far (ring buffer limits)
        self.clamped = 0  # records whose time was outside 1970..2106
        magic = PCAP_MAGIC_NANO if units == NANOS else PCAP_MAGIC
        stream.write(_GLOBAL_HEADER.pack(magic, 2, 4, 0, 0, SNAPLEN, linktype))
        if flush:
            stream.flush()

    def write(self, data: bytes, timestamp: float | None = None, comment: str | list[str] | None = None,
              original: int | None = None) -> None:
        """Append one record; without a timestamp (an untimed record), at the epoch: the previous one's time
        made an untimed input after a timed one timed (its answers '0.0 ms' after their requests), and so
        an untimed record inside a timed capture. pcap has no place for a comment: it is for pcapng's sake.
        `original`: the record's length on the line, more than its bytes' for a record captured in part (as
        editcap -s writes it; None: its bytes are all of it)."""
        if timestamp is None:  # (untimed: at the epoch, as the readers take it back: sources/pcap.py EpochRecord)
            timestamp = 0.0
        units = self._units
        seconds, fraction, moved = clamp_time(*split_time(timestamp, units), PCAP_SECONDS_MAX, units)
        self.clamped += moved
        # One write(2) a record (unbuffered streams): a reader never sees a header without its bytes.
        whole = len(data) if original is None else max(original, len(data))
        self._stream.write(_RECORD_HEADER.pack(seconds, fraction, len(data), whole) + data)
        self.size += _RECORD_HEADER.size + len(data)
        if self._flush:
            self._stream.flush()

    def use_interface(self, name: str | None, description: str | None, units: int | None = None) -> None:
        """pcap has no interface description: nothing to write (CaptureOutput warns of a lost line speed)."""

    def close(self) -> None:
        self._stream.close()
