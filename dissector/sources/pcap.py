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


def read_pcap(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    header = inp.read(FILE_HEADER_SIZE)
    magic = header[:4]
    if magic not in MAGICS:
        raise SourceError(f"{inp.name}: not a pcap file (magic {magic.hex() or 'missing'})")
    if len(header) < FILE_HEADER_SIZE:
        raise SourceError(
            f"{inp.name}: truncated pcap file header ({len(header)} of {FILE_HEADER_SIZE} bytes)"
        )
    order, units = MAGICS[magic]
    _major, _minor, _zone, _sigfigs, _snaplen, network = struct.unpack(order + "HHiIII", header[4:])
    # The upper bits of the link-type field hold FCS information, irrelevant to a serial line.
    linktype = network & 0xFFFF
    check_linktype(inp.name, linktype)
    record_header = struct.Struct(order + "IIII")
    record = 0
    while True:
        head = inp.read(RECORD_HEADER_SIZE)
        if not head:
            return
        record += 1
        if len(head) < RECORD_HEADER_SIZE:
            log.warn(
                "truncated input",
                f"record {record}: the capture ends inside its header ({len(head)} of 16 bytes)",
            )
            return
        seconds, fraction, captured, original = record_header.unpack(head)
        if captured < original:
            log.warn(
                "records captured in part",
                f"record {record}: only {captured} of its {original} bytes were captured",
            )
        # vw3-decode -w writes records at the epoch when its input had no times: keep them untimed.
        time = Stamp.from_parts(seconds, fraction, units) if seconds or fraction else None
        yield from record_chunks(inp, captured, time, linktype, record, log, chunk_size)
