"""Captures with records captured in part (a snapshot length shorter than the record), built byte by byte:
tests/differential/test_captured_in_part.py and tests/integration/test_lua_captured_in_part.py."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import rtu

T = 1_700_000_000
REQUEST, ANSWER, WRITE = rtu("02 03 20d1 0002"), rtu("02 03 04 0003 0002"), rtu("02 06 20d1 0001")
CAPTURES = Path(__file__).resolve().parents[2] / "captures"


def raw_pcap(path: Path, records: list[tuple[int, int, bytes]], snaplen: int = 65535) -> Path:
    """A pcap (USER0) of (microseconds after T, original length, captured bytes) records."""
    with path.open("wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, snaplen, 147))
        for micros, original, data in records:
            out.write(struct.pack("<IIII", T + micros // 1_000_000, micros % 1_000_000, len(data), original) + data)
    return path


def two_cut(tmp_path: Path) -> Path:
    """A read whose answer is captured in part (5 of 9 bytes), then a write captured in part (5 of 8), its echo
    whole, and the read again, answered whole."""
    return raw_pcap(tmp_path / "cut.pcap", [
        (0, 8, REQUEST), (10_000, 9, ANSWER[:5]), (100_000, 8, WRITE[:5]), (110_000, 8, WRITE),
        (200_000, 8, REQUEST), (210_000, 9, ANSWER),
    ])


CUT_ANSWER = "captured in part (5 of its 9 bytes; slave 2, function 3): its CRC cannot be checked"
# The answer's item once paired with its request #1 (decode/pairing.py _answer_in_part), and the request's note.
PAIRED_ANSWER = "captured in part (5 of its 9 bytes; slave 2, function 3; the answer to #1): its CRC cannot be checked"
CUT_WRITE = "captured in part (5 of its 8 bytes; slave 2, function 6): its CRC cannot be checked"


def records_of(path: Path) -> list[bytes]:
    """The captured bytes of every record of a little-endian classic pcap."""
    data = path.read_bytes()
    position, records = 24, []
    while position + 16 <= len(data):
        captured = struct.unpack_from("<I", data, position + 8)[0]
        records.append(data[position + 16 : position + 16 + captured])
        position += 16 + captured
    return records


def rtac_two_cut(tmp_path: Path) -> Path:
    """two_cut's records as an RTAC serial tap writes them (linktype 250: a 12-byte header, its own time, before
    the serial bytes; the record's lengths count it)."""
    path = tmp_path / "rtac.pcap"
    records = [(0, 8, REQUEST), (10_000, 9, ANSWER[:5]), (100_000, 8, WRITE[:5]), (110_000, 8, WRITE),
               (200_000, 8, REQUEST), (210_000, 9, ANSWER)]
    with path.open("wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 250))
        for micros, original, data in records:
            full = struct.pack(">IIBBH", T, micros, 0, 0, 0) + data
            out.write(struct.pack("<IIII", T, micros, len(full), original + 12) + full)
    return path
