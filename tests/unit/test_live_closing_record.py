"""Live -w's closing record (live_capture.CaptureFiles.close, CaptureOutput.close_at): a record of no byte at
the stop, in the file being written. A ring whose last file is full does not open the next file for it
(before: a file holding the closing record alone); none after nothing heard, none after a failed write."""
from __future__ import annotations

import struct
from pathlib import Path

from dissector.app.live_capture import CaptureFiles
from dissector.model import Noise, Stamp
from dissector.render.capturefile import open_output

T0 = 1_767_225_600_000_000_000  # ns


def records(path: Path) -> list[tuple[int, int]]:
    """(microseconds since T0, captured length) of a classic pcap's records."""
    data, at, out = path.read_bytes(), 24, []
    while at < len(data):
        seconds, micros, captured, _original = struct.unpack_from("<IIII", data, at)
        out.append((seconds * 1_000_000 + micros - T0 // 1000, captured))
        at += 16 + captured
    return out


def noise(index: int) -> Noise:
    return Noise(offset=600 * index, raw=bytes(600), time=Stamp(T0 + index * 1_000_000_000), reason="test")


def test_a_full_ring_file_takes_the_closing_record(tmp_path: Path) -> None:
    files = CaptureFiles(open_output(str(tmp_path / "ring.pcap"), None, ["filesize:1"], True, None), None)
    files.items([noise(0), noise(1)])  # (1,256 bytes: the file is full, the next record would open the next)
    files.close(Stamp(T0 + 2_500_000_000))
    written = sorted(tmp_path.glob("ring_*.pcap"))
    assert len(written) == 1 and records(written[0]) == [(0, 600), (1_000_000, 600), (2_500_000, 0)]


def test_none_after_nothing_or_a_failure(tmp_path: Path) -> None:
    quiet = CaptureFiles(open_output(str(tmp_path / "quiet.pcap"), None, (), True, None), None)
    quiet.close(Stamp(T0))
    assert records(tmp_path / "quiet.pcap") == []
    files = CaptureFiles(open_output(str(tmp_path / "once.pcap"), None, (), True, None), None)
    files.items([noise(0)])
    files.close()  # (as CaptureFiles._failed closes them)
    files.close(Stamp(T0 + 2_000_000_000))
    assert records(tmp_path / "once.pcap") == [(0, 600)]
