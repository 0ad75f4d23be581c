"""Modbus ASCII's alphabet and sizes, and how to tell an ASCII-mode byte stream from RTU."""
from __future__ import annotations

from dissector.protocol.crc import lrc

COLON, CR, LF = 0x3A, 0x0D, 0x0A
MAX_BINARY = 255  # slave + PDU (253) + LRC
MAX_ASCII = 1 + 2 * MAX_BINARY + 2  # ':' + hex pairs + CR LF
MIN_BINARY = 3  # slave, function, LRC

_HEX_DIGITS = frozenset(b"0123456789ABCDEFabcdef")
_ALPHABET = _HEX_DIGITS | {COLON, CR, LF}
ASCII_SHARE = 0.9  # share of ASCII-mode characters in a sample that makes it ASCII mode


def holds_frame(sample: bytes) -> bool:
    """Whether the sample holds a whole Modbus ASCII frame: ':', hex pairs (slave, function and LRC at
    least), LF (after CR, or alone: text files lose their CRs), its LRC good (the binary bytes and the
    LRC sum to 0 modulo 256).

    Whatever comes before it: a capture that starts mid-frame or after line noise. Binary RTU data
    practically never holds one (a ':', six or more hex digits, LF, and the sum: less than one chance
    in 10^13 at each byte of random data). One pass over the sample: each ':' is looked at once, and the
    hex digits after it are not looked at again.
    """
    at = sample.find(b":")
    while at >= 0:
        stop = at + 1
        while stop < len(sample) and sample[stop] in _HEX_DIGITS:
            stop += 1
        digits = stop - at - 1
        ends = sample[stop : stop + 1] == b"\n" or sample[stop : stop + 2] == b"\r\n"
        if ends and digits % 2 == 0 and digits >= 2 * MIN_BINARY:
            binary = bytes.fromhex(sample[at + 1 : stop].decode("ascii"))
            if lrc(binary[:-1]) == binary[-1]:
                return True
        at = sample.find(b":", stop)  # (the digits hold no ':')
    return False


def detect_mode(first_bytes: bytes) -> str:
    """'ascii' when the first bytes of a stream look like Modbus ASCII, else 'rtu'.

    ASCII when they hold a whole ASCII frame with a good LRC (holds_frame), whatever noise comes
    before it; or, where no frame is whole in them (a first frame longer than the sample, bad LRCs), when
    a ':' is followed by hex digits and nine bytes in ten are hex digits, ':', CR or LF (binary RTU
    data is spread over all 256 byte values).
    """
    if holds_frame(first_bytes):
        return "ascii"
    colon = first_bytes.find(b":")
    if colon < 0:
        return "rtu"
    following = first_bytes[colon + 1 : colon + 3]
    if not following or any(byte not in _HEX_DIGITS for byte in following):
        return "rtu"
    inside = sum(1 for byte in first_bytes if byte in _ALPHABET)
    return "ascii" if inside >= ASCII_SHARE * len(first_bytes) else "rtu"
