"""An RTAC serial capture (link type 250) counts its -t r and -t d times from its packets, as tshark's
frame.time_relative and frame.time_delta: a record of the RTAC header alone (an event, no serial byte) is a packet
tshark shows, no item. Each packet's time is its RTAC header's, as -t a/e and the response times take it (equal
to the record's in these captures, the usual case). Before, the bus counted from its own items: the first request
showed 0.000000 where tshark shows 0.001000 (the event record before it), the answer after an event record
-t d 0.008000 where tshark shows 0.006000; -V said `since the first item`. Engine and VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import struct
import sys
from pathlib import Path

import pytest
from helpers import run_cli, use_engine

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "differential"))  # (collected alone: not on the path)
from test_timed_summary import decode  # noqa: E402
from test_several_interface_times import _tsharks  # noqa: E402

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")
T0 = 1_767_225_600  # 2026-01-01 00:00:00 UTC
ETHERNET = bytes(60)
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# (microseconds after T0, event type, serial bytes): an event first, a poll, an event between request and answer
# (0x01, data transmit start: no trouble warned), a second poll.
RECORDS = [(0, 0x01, b""), (1000, 0, REQUEST), (3000, 0x01, b""), (9000, 0, ANSWER), (500_000, 0, REQUEST),
           (520_000, 0, ANSWER)]
ITEM_FRAMES = ["2", "4", "5", "6"]  # tshark's frame of each item


def _rtac(micros: int, event: int, data: bytes) -> bytes:
    seconds, fraction = divmod(T0 * 1_000_000 + micros, 1_000_000)
    return struct.pack(">IIBBH", seconds, fraction, event, 0, 0) + data


def _pcap(path: Path, stored: list[int] | None = None) -> Path:
    """`stored`: each record's time (us after T0) where it is not its header's."""
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 250)
    for (micros, event, data), at in zip(RECORDS, stored or [micros for micros, _event, _data in RECORDS]):
        payload = _rtac(micros, event, data)
        seconds, fraction = divmod(T0 * 1_000_000 + at, 1_000_000)
        out += struct.pack("<IIII", seconds, fraction, len(payload), len(payload)) + payload
    path.write_bytes(out)
    return path


def _block(kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def _pcapng(path: Path, linktypes: list[int], packets: list[tuple[int, int, bytes]]) -> Path:
    """Interfaces (their link types) and packets (interface, microseconds after T0, bytes)."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for linktype in linktypes:
        out += _block(1, struct.pack("<HHI", linktype, 0, 0))
    for interface, micros, data in packets:
        stamp = T0 * 1_000_000 + micros
        out += _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data)
    path.write_bytes(out)
    return path


def _alone(path: Path) -> Path:
    return _pcapng(path, [250], [(0, micros, _rtac(micros, event, data)) for micros, event, data in RECORDS])


def _beside(path: Path) -> Path:
    """The RTAC interface beside an Ethernet one, whose packets come first and between."""
    packets = [(1, micros, _rtac(micros, event, data)) for micros, event, data in RECORDS]
    packets += [(0, 500, ETHERNET), (0, 7000, ETHERNET)]
    return _pcapng(path, [1, 250], sorted(packets, key=lambda packet: packet[1]))


WRITERS = pytest.mark.parametrize("write", [_pcap, _alone], ids=["pcap", "pcapng"])


def _column(path: Path, *options: str) -> list[str]:
    status, out, _err = run_cli([*options, str(path)])  # (beside Ethernet: its interface's warning)
    assert status == 0
    return [line[8:19].strip() for line in out.splitlines()]


@BOTH
@WRITERS
def test_the_time_columns_count_the_packets(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                            write) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "rtac.cap")
    assert _column(path, "-t", "r") == ["0.001000", "0.009000", "0.500000", "0.520000"]
    assert _column(path, "-t", "d") == ["0.001000", "0.006000", "0.491000", "0.020000"]
    # (no sample read for its mode: the pcapng's interface not yet described when its clock is set)
    assert _column(path, "--mode", "rtu", "-t", "d") == ["0.001000", "0.006000", "0.491000", "0.020000"]
    assert _column(path, "-t", "dd") == ["0.000000", "0.008000", "0.491000", "0.020000"]  # (the items shown)
    status, fields, err = run_cli(["-T", "fields", "-e", "time_relative", "-e", "time_delta", str(path)])
    theirs = _tsharks(path)
    assert fields.splitlines() == [theirs[frame] for frame in ITEM_FRAMES]
    assert fields.splitlines()[:2] == ["0.001000000\t0.001000000", "0.009000000\t0.006000000"]


@BOTH
def test_beside_ethernet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """In a pcapng with an Ethernet interface too, its packets count as well (frames 2 and 5 are Ethernet)."""
    use_engine(monkeypatch, pure)
    path = _beside(tmp_path / "beside.pcapng")
    assert _column(path, "-t", "r") == ["0.001000", "0.009000", "0.500000", "0.520000"]
    assert _column(path, "-t", "d") == ["0.000500", "0.002000", "0.491000", "0.020000"]
    status, fields, err = run_cli(["-T", "fields", "-e", "time_relative", "-e", "time_delta", str(path)])
    theirs = _tsharks(path)
    assert fields.splitlines() == [theirs[frame] for frame in ["3", "6", "7", "8"]]


@BOTH
@WRITERS
def test_detail_says_since_the_first_packet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                            write) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    out = run_cli(["-V", str(write(tmp_path / "rtac.cap"))])[1]
    assert [line for line in out.splitlines() if "Arrival" in line][:2] == [
        "    Arrival time: 2026-01-01 00:00:00.001000 UTC (0.001000 s since the first packet)",
        "    Arrival time: 2026-01-01 00:00:00.009000 UTC (0.009000 s since the first packet)"]


@WRITERS
@pytest.mark.parametrize("time_format", ["r", "d", "dd"])
def test_the_engine_writes_them(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, write,  # type: ignore[no-untyped-def]
                                time_format: str) -> None:
    path = write(tmp_path / "rtac.cap")
    fast, engine_lines = decode(["-t", time_format, str(path)], monkeypatch, pure=False)
    reference, none = decode(["-t", time_format, str(path)], monkeypatch, pure=True)
    assert (fast, none) == (reference, 0)
    assert engine_lines == 4


@BOTH
def test_the_header_clock_where_the_record_clock_differs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         pure: bool) -> None:
    """Records stored late and unevenly (their times 2 s on, the first event's 2.4 s): the columns count the RTAC
    header's times, as -t a and the response times show them, where tshark's frame times are the records'."""
    use_engine(monkeypatch, pure)
    path = _pcap(tmp_path / "late.pcap", [2_400_000, 2_001_000, 2_003_000, 2_100_000, 2_500_000, 2_520_000])
    assert _column(path, "-t", "r") == ["0.001000", "0.009000", "0.500000", "0.520000"]
    assert _column(path, "-t", "d") == ["0.001000", "0.006000", "0.491000", "0.020000"]
    out = run_cli(["-t", "ud", str(path)])[1]
    assert out.splitlines()[0].startswith("     1 2026-01-01 00:00:00.001000  12 request")  # (the header's)
