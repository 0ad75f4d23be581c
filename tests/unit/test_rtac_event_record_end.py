"""An RTAC serial record of the 12-byte header alone (an RTAC event: a serial break, a control line change)
carries no serial byte, yet its own time says the tap was recording then, as an empty USER0 record's does
(test_capture_end_interfaces.py): a request the capture runs on past its timeout without an answer is
unanswered. Before, such a record yielded no chunk and its time was lost (pcap.py and pcapng.py take an
RTAC record's time from its bytes, not its record header), so the capture "ended" at the request: "not
known whether it was answered", 0 in --stats' no reply, where the same file as USER0 said [no response]
and tshark shows the event 3 s later."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")
T0 = 1_700_000_000
THIRD = "     3     1.000000  12 request   Read Holding Registers 8400..8402 (3) "
UNANSWERED = THIRD + "[no response]  CRC ok"
WITHIN = (THIRD + "[the capture ends 500.0 ms after the request, within the 1000 ms timeout: not known "
          "whether it was answered]  CRC ok")
NO_REPLY = "   12  3 Read Holding Registers    2     1                     {}        0"


def _records(last: float) -> list[tuple[float, bytes]]:
    """(seconds after T0, RTAC payload): a read answered, a read at 1 s, then at `last` an event record
    of the header alone (event 0x01: data transmit start, no data)."""
    def rtac(at: float, data: bytes, event: int = 0) -> tuple[float, bytes]:
        micros = round(at * 1_000_000)
        return at, struct.pack(">IIBBH", T0 + micros // 1_000_000, micros % 1_000_000, event, 0, 0) + data

    return [rtac(0, REQUEST), rtac(0.012, ANSWER), rtac(1, REQUEST), rtac(last, b"", event=0x01)]


def _pcap(path: Path, last: float) -> Path:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 250)
    for at, payload in _records(last):
        micros = round(at * 1_000_000)
        out += struct.pack("<IIII", T0 + micros // 1_000_000, micros % 1_000_000, len(payload), len(payload))
        out += payload
    path.write_bytes(out)
    return path


def _block(kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def _pcapng(path: Path, last: float) -> Path:
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    out += _block(1, struct.pack("<HHI", 250, 0, 0))
    for at, payload in _records(last):
        stamp = (T0 * 1_000_000) + round(at * 1_000_000)
        out += _block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(payload), len(payload))
                      + payload)
    path.write_bytes(out)
    return path


@BOTH
@pytest.mark.parametrize("write", [_pcap, _pcapng], ids=["pcap", "pcapng"])
@pytest.mark.parametrize("last, expected", [(4.0, UNANSWERED), (1.5, WITHIN)], ids=["past", "within"])
def test_an_event_record_ends_the_capture(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                          write, last: float, expected: str) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "rtac.cap", last)
    status, out, err = run_cli([str(path)])
    assert (status, err) == (0, "")
    assert out.splitlines()[-1] == expected
    status, out, err = run_cli([str(path), "--stats"])
    assert [line for line in out.splitlines() if line.startswith("   12  3 Read")][:1] == [
        NO_REPLY.format(1 if expected == UNANSWERED else 0)]
