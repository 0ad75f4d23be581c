"""Modbus ASCII's alphabet and sizes, and how to tell an ASCII-mode byte stream from RTU."""
from __future__ import annotations

from dissector.protocol.crc import crc_lengths, lrc
from dissector.protocol.spec import SPEC
from dissector.protocol.table import SCAN

COLON, CR, LF = 0x3A, 0x0D, 0x0A
MAX_BINARY = 255  # slave + PDU (253) + LRC
MAX_ASCII = 1 + 2 * MAX_BINARY + 2  # ':' + hex pairs + CR LF
MIN_BINARY = 3  # slave, function, LRC

_HEX_DIGITS = frozenset(b"0123456789ABCDEFabcdef")
_ALPHABET = _HEX_DIGITS | {COLON, CR, LF}
ASCII_SHARE = 0.9  # share of ASCII-mode characters in a sample that makes it ASCII mode
MODE_SAMPLE = 64  # the first bytes of a stream that tell its mode when they hold an ASCII frame
# How far the sample grows while it cannot tell: noise as long as the longest frame, then that frame
MODE_REACH = 2 * MAX_ASCII
# (RTU frames: a slave address, a public function code or its exception, at least MIN_ADU bytes with the CRC)
_PUBLIC = frozenset(SPEC.functions)
_MAX_SLAVE, _MAX_ADU, _MIN_ADU = int(SPEC.limits["max_slave"]), int(SPEC.limits["max_adu"]), SCAN.minimum


def frame_end(sample: bytes) -> int | None:
    """Where the first whole Modbus ASCII frame in the sample ends (None: none): ':', hex pairs (slave,
    function and LRC at least), LF (after CR, or alone: text files lose their CRs), its LRC good (the
    binary bytes and the LRC sum to 0 modulo 256).

    Whatever comes before it: a capture that starts mid-frame or after line noise. Binary RTU data
    practically never holds one (a ':', six or more hex digits, LF, and the sum: less than one chance
    in 10^13 at each byte of random data). One pass over the sample: each ':' is looked at once, and the
    hex digits after it are not looked at again (so the first frame found is the first to end).
    """
    at = sample.find(b":")
    while at >= 0:
        stop = at + 1
        while stop < len(sample) and sample[stop] in _HEX_DIGITS:
            stop += 1
        digits = stop - at - 1
        line_end = 1 if sample[stop : stop + 1] == b"\n" else 2 if sample[stop : stop + 2] == b"\r\n" else 0
        if line_end and digits % 2 == 0 and digits >= 2 * MIN_BINARY:
            binary = bytes.fromhex(sample[at + 1 : stop].decode("ascii"))
            if lrc(binary[:-1]) == binary[-1]:
                return stop + line_end
        at = sample.find(b":", stop)  # (the digits hold no ':')
    return None


def holds_frame(sample: bytes) -> bool:
    """Whether the sample holds a whole Modbus ASCII frame with a good LRC (frame_end)."""
    return frame_end(sample) is not None


def _rtu_start(sample: bytes, at: int) -> bool:
    return sample[at] <= _MAX_SLAVE and sample[at + 1] & 0x7F in _PUBLIC


def rtu_pair_end(sample: bytes) -> int | None:
    """Where the first two RTU frames back to back end in the sample (None: none), each a slave address,
    a public function code (or its exception) and bytes ending in their CRC.

    One frame alone is no evidence: its CRC matches one length in 65,536 by chance, and it may be up to
    MAX_ADU bytes long (a scan of 60 random bytes finds one about once in 30); two back to back, practically
    never. ASCII text starts none (no hex digit, ':', CR or LF is a public function code). The pairs are
    looked for only where they would end before the best so far.
    """
    best = None
    for start in range(len(sample) - 2 * _MIN_ADU + 1):
        if start + 2 * _MIN_ADU > (len(sample) if best is None else best - 1):
            break
        if not _rtu_start(sample, start):
            continue
        first_last = (len(sample) if best is None else best - 1) - _MIN_ADU - start
        for length in crc_lengths(sample, start, _MIN_ADU, min(first_last, _MAX_ADU)):
            second = start + length
            last = len(sample) if best is None else best - 1  # (the furthest a better pair ends)
            if second + _MIN_ADU <= last and _rtu_start(sample, second):
                lengths = crc_lengths(sample, second, _MIN_ADU, min(last - second, _MAX_ADU))
                if lengths:
                    best = second + lengths[0]
    return best


def sample_mode(sample: bytes, complete: bool) -> str | None:
    """The mode a stream's first bytes give: 'ascii' or 'rtu', or None while they cannot tell yet (more
    bytes are to come: `complete` false).

    ASCII when the first MODE_SAMPLE bytes hold a whole ASCII frame (frame_end). Otherwise the sample
    grows, up to MODE_REACH bytes, until a whole ASCII frame or two RTU frames back to back
    (rtu_pair_end) end in it: the first to end tells (a capture that starts with more line noise than
    MODE_SAMPLE; a normal RTU bus is told in its first MODE_SAMPLE bytes, as before). Where neither has
    come by MODE_REACH bytes or the end of the input: detect_mode. An answer given while more bytes can
    come is the answer for any longer sample: whatever pieces the bytes come in (reader.py's chunks, the
    plugin's records: lua/src/dissector.lua), the mode is the same.
    """
    if len(sample) < MODE_SAMPLE and not complete:
        return None
    if holds_frame(sample[:MODE_SAMPLE]):
        return "ascii"
    sample = sample[:MODE_REACH]
    ascii_end, rtu_end = frame_end(sample), rtu_pair_end(sample)
    if rtu_end is not None and (ascii_end is None or rtu_end < ascii_end):
        return "rtu"
    if ascii_end is not None:
        return "ascii"
    if complete or len(sample) >= MODE_REACH:
        return detect_mode(sample)
    return None


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
