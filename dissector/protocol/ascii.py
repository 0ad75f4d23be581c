"""Modbus ASCII's alphabet and sizes, and how to tell an ASCII-mode byte stream from RTU."""
from __future__ import annotations

COLON, CR, LF = 0x3A, 0x0D, 0x0A
MAX_BINARY = 255  # slave + PDU (253) + LRC
MAX_ASCII = 1 + 2 * MAX_BINARY + 2  # ':' + hex pairs + CR LF
MIN_BINARY = 3  # slave, function, LRC

_HEX_DIGITS = frozenset(b"0123456789ABCDEFabcdef")
_ALPHABET = _HEX_DIGITS | {COLON, CR, LF}
ASCII_SHARE = 0.9  # share of ASCII-mode characters in a sample that makes it ASCII mode


def detect_mode(first_bytes: bytes) -> str:
    """'ascii' when the bytes look like Modbus ASCII (a ':' then hex pairs, almost nothing else).

    Binary RTU data is spread over all 256 byte values; a sample where nine bytes in ten are hex
    digits, ':', CR or LF, with a ':' followed by hex, is ASCII mode.
    """
    colon = first_bytes.find(b":")
    if colon < 0:
        return "rtu"
    following = first_bytes[colon + 1 : colon + 3]
    if not following or any(byte not in _HEX_DIGITS for byte in following):
        return "rtu"
    inside = sum(1 for byte in first_bytes if byte in _ALPHABET)
    return "ascii" if inside >= ASCII_SHARE * len(first_bytes) else "rtu"
