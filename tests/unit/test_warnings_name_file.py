"""With several captures on the command line, a warning that numbers a record names its file, as the ==> title
over the file's items does: `record 1: only 5 of its 8 bytes were captured` alone could be any file's
(hunt63). One capture's warnings are as they were."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli

REQUEST = bytes.fromhex("0C 03 20 D0 00 03 0E EF")  # VW3 A3 303 p.38's read of 8400..8402 (3)


def _pcap(path: Path, captured: int) -> str:
    """A one-record pcap (linktype 147) of REQUEST, `captured` of its 8 bytes kept."""
    header = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    record = struct.pack("<IIII", 1_767_225_600, 0, captured, len(REQUEST)) + REQUEST[:captured]
    path.write_bytes(header + record)
    return str(path)


def test_each_file_named_in_its_record_warnings(tmp_path: Path) -> None:
    first, second = _pcap(tmp_path / "a.pcap", 5), _pcap(tmp_path / "b.pcap", 6)
    status, out, err = run_cli(["-q", "--stats", first, second])
    assert status == 0
    assert [line for line in err.splitlines() if "captured" in line] == [
        f"vw3-decode: warning: {first}: record 1: only 5 of its 8 bytes were captured",
        f"vw3-decode: warning: {first}: no frame can be checked: every record was captured in part (1 record, "
        "5 bytes: a snapshot length shorter than the frames), their CRCs cut off: capture again with a larger "
        "snapshot length",
        f"vw3-decode: warning: {second}: record 1: only 6 of its 8 bytes were captured",
        f"vw3-decode: warning: {second}: no frame can be checked: every record was captured in part (1 record, "
        "6 bytes: a snapshot length shorter than the frames), their CRCs cut off: capture again with a larger "
        "snapshot length",
    ]


def test_one_file_unchanged(tmp_path: Path) -> None:
    status, out, err = run_cli([_pcap(tmp_path / "a.pcap", 5)])
    assert status == 0
    assert err.splitlines()[0] == "vw3-decode: warning: record 1: only 5 of its 8 bytes were captured"
