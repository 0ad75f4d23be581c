"""The line on standard error that says where a pcapng's packet comments are names the bus they are on, and so
does a warning that numbers a record (a record captured in part, one cut short).
A pcapng with packets of two serial interfaces (Wireshark capturing two lines) is decoded as two buses,
each numbering its own records: the comment on the file's second packet is record 1 of the second bus
(tshark: frame 2). The line named the file alone, "FILE: 1 packet comment (record 1)", which sent the
reader to the first bus's record 1, a packet with no comment."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli

REQUEST_A = bytes.fromhex("0C0320D000030EEF")
ANSWER_A = bytes.fromhex("0C0306000100020003A5E4")
T0 = 1_767_225_600_000_000  # 2026-01-01 in microseconds


def _block(kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def _option(code: int, value: bytes) -> bytes:
    return struct.pack("<HH", code, len(value)) + value + b"\0" * (-len(value) % 4)


def _packet(interface: int, micros: int, data: bytes, comment: str | None, original: int = 0) -> bytes:
    stamp = T0 + micros
    options = _option(1, comment.encode()) + b"\0" * 4 if comment else b""
    return _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data),
                                 original or len(data)) + data + b"\0" * (-len(data) % 4) + options)


def two_lines(tmp_path: Path) -> Path:
    """Interfaces /dev/ttyA and /dev/ttyB; one comment, on the file's second packet (ttyB's first)."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for name in (b"/dev/ttyA", b"/dev/ttyB"):
        out += _block(1, struct.pack("<HHI", 147, 0, 0) + _option(2, name) + b"\0" * 4)
    out += _packet(0, 0, REQUEST_A, None)
    out += _packet(1, 1_000, REQUEST_A, "line B polled")
    out += _packet(0, 10_000, ANSWER_A, None)
    out += _packet(1, 11_000, ANSWER_A, None)
    path = tmp_path / "c.pcapng"
    path.write_bytes(out)
    return path


def test_the_comment_line_names_the_bus(tmp_path: Path) -> None:
    path = two_lines(tmp_path)
    status, out, err = run_cli([str(path)])
    assert status == 0
    assert out.splitlines()[3] == f"==> {path}: /dev/ttyB <=="
    assert err == f"vw3-decode: {path}: /dev/ttyB: 1 packet comment (record 1): -V and --json show them\n"


def test_a_pcap_copy_names_the_bus_of_the_comment_not_kept(tmp_path: Path) -> None:
    path = two_lines(tmp_path)
    copy = tmp_path / "copy.pcap"
    status, _out, err = run_cli([str(path), "-q", "-w", str(copy)])
    assert status == 0
    assert err.splitlines()[-1] == (f"vw3-decode: warning: -w {copy}: pcap has no packet comments: the 1 packet comment "
                   f"(record 1) of {path}: /dev/ttyB is not kept (write pcapng, -F pcapng, to keep them)")


def test_a_record_warning_names_the_bus(tmp_path: Path) -> None:
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for name in (b"/dev/ttyA", b"/dev/ttyB"):
        out += _block(1, struct.pack("<HHI", 147, 0, 0) + _option(2, name) + b"\0" * 4)
    out += _packet(0, 0, REQUEST_A, None) + _packet(1, 1_000, REQUEST_A, None)
    out += _packet(0, 10_000, ANSWER_A, None) + _packet(1, 11_000, ANSWER_A[:5], None, original=11)
    path = tmp_path / "cut.pcapng"
    path.write_bytes(out)
    status, _out, err = run_cli([str(path), "-q"])
    assert status == 0
    assert err == f"vw3-decode: warning: {path}: /dev/ttyB: record 2: only 5 of its 11 bytes were captured\n"
