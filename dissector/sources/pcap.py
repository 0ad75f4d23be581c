"""Classic pcap (libpcap) files: both byte orders, microsecond and nanosecond timestamps.

A record is one read of the serial line (one frame for most sniffers, any run of bytes for others):
it becomes one Chunk with the record's time and boundary=True. Only the link types that carry raw
serial bytes are accepted (common.SUPPORTED_LINKTYPES); anything else is an error, not noise.
"""
from __future__ import annotations

import struct
from collections.abc import Iterator

from dissector.model import Chunk, Stamp
from dissector.sources.common import Input, SourceError, WarningLog, check_linktype, record_chunks

# Magic as the first four bytes of the file -> (struct byte order, timestamp fraction units).
MAGICS: dict[bytes, tuple[str, int]] = {
    bytes.fromhex("d4c3b2a1"): ("<", 1_000_000),
    bytes.fromhex("a1b2c3d4"): (">", 1_000_000),
    bytes.fromhex("4d3cb2a1"): ("<", 1_000_000_000),
    bytes.fromhex("a1b23c4d"): (">", 1_000_000_000),
}
FILE_HEADER_SIZE = 24
RECORD_HEADER_SIZE = 16


def is_pcap(head: bytes) -> bool:
    return head[:4] in MAGICS


def read_pcap(inp: Input, log: WarningLog, chunk_size: int) -> PcapRecords:
    return PcapRecords(inp, log, chunk_size)


class PcapRecords:
    """The chunks of a pcap's records (an iterator); `blocks` reads the rest in bulk (accel/records.py)."""

    def __init__(self, inp: Input, log: WarningLog, chunk_size: int) -> None:
        self.inp = inp
        self.log = log
        self.chunk_size = chunk_size
        self.record = 0
        self.between = False  # the last chunk given ended a record: the next bytes are a record header
        self.order, self.units, self.linktype = "<", 1_000_000, 0
        self._chunks = self._read()

    def __iter__(self) -> PcapRecords:
        return self

    def __next__(self) -> Chunk:
        chunk = next(self._chunks)
        self.between = chunk.boundary
        return chunk

    def _read(self) -> Iterator[Chunk]:
        inp = self.inp
        header = inp.read(FILE_HEADER_SIZE)
        magic = header[:4]
        if magic not in MAGICS:
            raise SourceError(f"{inp.name}: not a pcap file (magic {magic.hex() or 'missing'})")
        if len(header) < FILE_HEADER_SIZE:
            raise SourceError(
                f"{inp.name}: truncated pcap file header ({len(header)} of {FILE_HEADER_SIZE} bytes)"
            )
        self.order, self.units = MAGICS[magic]
        _major, _minor, _zone, _sigfigs, _snaplen, network = struct.unpack(self.order + "HHiIII", header[4:])
        # The upper bits of the link-type field hold FCS information, irrelevant to a serial line.
        self.linktype = network & 0xFFFF
        check_linktype(inp.name, self.linktype)
        yield from self.records(inp)

    def records(self, inp: Input) -> Iterator[Chunk]:
        """The chunks of the records `inp` holds from its position on."""
        log = self.log
        record_header = struct.Struct(self.order + "IIII")
        while True:
            head = inp.read(RECORD_HEADER_SIZE)
            if not head:
                return
            self.record += 1
            if len(head) < RECORD_HEADER_SIZE:
                log.warn(
                    "truncated input",
                    f"record {self.record}: the capture ends inside its header ({len(head)} of 16 bytes)",
                )
                return
            seconds, fraction, captured, original = record_header.unpack(head)
            if captured < original:
                log.warn(
                    "records captured in part",
                    f"record {self.record}: only {captured} of its {original} bytes were captured",
                )
            # vw3-decode -w writes records at the epoch when its input had no times: keep them untimed.
            time = Stamp.from_parts(seconds, fraction, self.units) if seconds or fraction else None
            yield from record_chunks(inp, captured, time, self.linktype, self.record, log, self.chunk_size)
