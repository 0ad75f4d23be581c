"""CRC-16/MODBUS and the ASCII-mode LRC.

`crc16` is the Rust implementation from fastcrc (about 20x faster than a Python loop, and CRC is the
largest single cost of framing); `crc16_reference` is the plain table-driven algorithm the tests hold
it against.
"""
from __future__ import annotations

from fastcrc import crc16 as _fastcrc16

crc16 = _fastcrc16.modbus


def _make_table() -> list[int]:
    table = []
    for byte in range(256):
        crc = byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
        table.append(crc)
    return table


_TABLE = _make_table()


def crc16_reference(data: bytes) -> int:
    """CRC-16/MODBUS: reflected polynomial 0xA001, initial value 0xFFFF. Sent low byte first."""
    crc = 0xFFFF
    for byte in data:
        crc = (crc >> 8) ^ _TABLE[(crc ^ byte) & 0xFF]
    return crc


def _crc_lengths_python(buf: bytes | bytearray, start: int, minimum: int, maximum: int) -> list[int]:
    maximum = min(maximum, len(buf) - start)
    minimum = max(minimum, 2)
    if minimum > maximum:
        return []
    table = _TABLE
    crc = crc16(bytes(buf[start : start + minimum - 2]))
    lengths = []
    for stop in range(start + minimum - 2, start + maximum - 1):
        if crc == buf[stop] | buf[stop + 1] << 8:
            lengths.append(stop + 2 - start)
        crc = (crc >> 8) ^ table[(crc ^ buf[stop]) & 0xFF]
    return lengths


try:  # the compiled path's module has the same function in C (a scan is ~250 CRC steps)
    from dissector.accel._summary import crc_lengths as _crc_lengths_compiled
except ImportError:
    _crc_lengths_compiled = None


def crc_lengths(buf: bytes | bytearray, start: int, minimum: int, maximum: int) -> list[int]:
    """Every length L in minimum..maximum at which buf[start:start + L] ends in the CRC of the bytes
    before it: a frame without a length rule is found by this scan. One incremental pass, instead of
    one CRC per candidate length (which made a stream of random bytes decode at 40 KB/s)."""
    if _crc_lengths_compiled is not None:
        return _crc_lengths_compiled(buf, start, minimum, maximum)
    return _crc_lengths_python(buf, start, minimum, maximum)


def crc_bytes(data: bytes) -> bytes:
    """The two check bytes as they go on the wire (low byte first)."""
    return crc16(data).to_bytes(2, "little")


def with_crc(data: bytes) -> bytes:
    return data + crc_bytes(data)


def lrc(data: bytes) -> int:
    """Modbus ASCII LRC: two's complement of the 8-bit sum of the binary bytes."""
    return (-sum(data)) & 0xFF
