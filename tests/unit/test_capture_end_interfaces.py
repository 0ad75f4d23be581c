"""A capture ends when its tap last recorded: the file's last record, of any interface and empty or not
(sources/pcapng.py PcapngChunks.recorded_until, Dissector's `recorded`). Each interface of a pcapng is its
own bus (sources/interfaces.py), but the tap recorded every line until the file's last record: a request
at the end of bus A with bus B's records going on past its timeout was never answered. Before, bus A's
capture ended with its own last record ("the capture ends before any response: not known whether it was
answered") and the request was not counted (no reply, -Y unanswered, the bus timing's outages, parquet).
An empty record (0 bytes) says as much of a single-interface file, pcapng or pcap: the tap was recording then.
"""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from test_pcapng_interfaces import ANSWER_A, ANSWER_B, READ, REQUEST, _pcapng

from dissector.sources.common import Input, WarningLog
from dissector.sources.pcapng import read_pcapng

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# Bus A: a read answered, then a read at 1 s that nothing answers; bus B's reads go on to `until` (us).
BUS_A = [(0, 0, REQUEST), (0, 10_000, ANSWER_A), (0, 1_000_000, REQUEST)]
# Ten reads answered, for a pcap: the engine reads the records after the mode's sample in bulk.
POLLS = [(n * 50_000 + at, data) for n in range(10) for at, data in ((0, REQUEST), (10_000, ANSWER_A))]
ANSWERED = ("     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 "
            "8402=2 [#1, 10.0 ms]  CRC ok")
THIRD = "     3     1.000000  12 request   Read Holding Registers 8400..8402 (3) "
UNANSWERED = THIRD + "[no response]  CRC ok"  # (past the timeout: as when later bytes tell, no note)
WITHIN = (THIRD + "[the capture ends 200.0 ms after the request, within the 1000 ms timeout: not known "
          "whether it was answered]  CRC ok")
ENDS = [(3_012_000, UNANSWERED), (1_200_000, WITHIN)]  # the file's last record, and bus A's last line
NO_REPLY = "   12  3 Read Holding Registers    2     1                     {}        0"


def _two_buses(path: Path, until: int) -> Path:
    bus_b = [(1, 2000, REQUEST), (1, 12_000, ANSWER_B), (1, until - 10_000, REQUEST), (1, until, ANSWER_B)]
    path.write_bytes(_pcapng(["A", "B"], sorted(BUS_A + bus_b, key=lambda packet: packet[1])))
    return path


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> list[str]:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    return out.splitlines()


@BOTH
def test_other_bus_records_past_the_timeout_end_the_wait(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         pure: bool) -> None:
    path = _two_buses(tmp_path / "two.pcapng", 3_012_000)  # bus B's records go on 2 s after A's last request
    lines = _decode([str(path)], monkeypatch, pure)
    assert lines[:4] == [f"==> {path}: A <==", f"     1     0.000000  {READ}", ANSWERED, UNANSWERED]
    assert lines[4] == f"==> {path}: B <=="
    assert _decode([str(path), "-Y", "unanswered"], monkeypatch, pure) == [
        f"==> {path}: A <==", UNANSWERED]  # (bus B has no match: no title over nothing)
    stats = _decode([str(path), "--stats"], monkeypatch, pure)
    assert [line for line in stats if line.startswith("   12  3 Read")][:1] == [NO_REPLY.format(1)]


@BOTH
def test_other_bus_records_within_the_timeout_leave_it_unknown(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    path = _two_buses(tmp_path / "two.pcapng", 1_200_000)  # the file's last record: 200 ms after A's request
    lines = _decode([str(path)], monkeypatch, pure)
    assert lines[:4] == [f"==> {path}: A <==", f"     1     0.000000  {READ}", ANSWERED, WITHIN]
    stats = _decode([str(path), "--stats"], monkeypatch, pure)
    assert [line for line in stats if line.startswith("   12  3 Read")][:1] == [NO_REPLY.format(0)]


@BOTH
@pytest.mark.parametrize("until, last", ENDS, ids=["past", "within"])
def test_an_empty_last_record_says_the_tap_recorded(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    pure: bool, until: int, last: str) -> None:
    # One interface: its last record holds no byte, `until` microseconds in. The same rule as another bus's
    # record: bus A's outputs are those of the two-bus file whose records go on as long.
    path = tmp_path / "one.pcapng"
    path.write_bytes(_pcapng(["A"], BUS_A + [(0, until, b"")]))
    assert _decode([str(path)], monkeypatch, pure) == [f"     1     0.000000  {READ}", ANSWERED, last]
    two = _two_buses(tmp_path / "two.pcapng", until)
    stats = _decode([str(two), "--stats"], monkeypatch, pure)
    bus_a = stats[1 : stats.index(f"==> {two}: B <==") - 1]
    assert _decode([str(path), "--stats"], monkeypatch, pure) == bus_a


def test_recorded_until_is_the_last_timed_record_of_any_interface(tmp_path: Path) -> None:
    path = tmp_path / "two.pcapng"
    path.write_bytes(_pcapng(["A", "B"], BUS_A + [(1, 2_500_000, REQUEST), (1, 3_000_000, b"")]))
    with open(path, "rb") as stream:
        chunks = read_pcapng(Input(stream, str(path)), WarningLog(), 1 << 16, only=0)
        assert chunks.recorded_until is None  # (nothing read yet)
        assert [chunk.data for chunk in chunks] == [REQUEST, ANSWER_A, REQUEST]
    assert chunks.recorded_until is not None and chunks.recorded_until.ns == 1_767_225_603_000_000_000


def test_parquet_counts_the_request_unanswered(tmp_path: Path) -> None:
    pq = pytest.importorskip("pyarrow.parquet")
    path = _two_buses(tmp_path / "two.pcapng", 3_012_000)
    status, out, err = run_cli(["--parquet", str(tmp_path / "pq"), str(path)])
    assert (status, err) == (0, "")
    first = pq.read_table(sorted((tmp_path / "pq" / "frames").iterdir())[0])
    assert first.column("unanswered").to_pylist() == [False, None, True]
    assert first.column("notes").to_pylist()[2] == []


def _pcap(records: list[tuple[int, bytes]]) -> bytes:
    """A classic pcap (LINKTYPE_USER0): records (microseconds, bytes) from 2026-01-01."""
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    for micros, data in records:
        seconds, fraction = divmod(1_767_225_600_000_000 + micros, 1_000_000)
        out += struct.pack("<IIII", seconds, fraction, len(data), len(data)) + data
    return out


@BOTH
@pytest.mark.parametrize("until, unanswered", [(3_012_000, True), (1_200_000, False)], ids=["past", "within"])
def test_a_pcap_empty_last_record_too(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, until: int,
                                      unanswered: bool) -> None:
    # (the engine's bulk read passes over empty records: accel/records.py last_record_time)
    path = tmp_path / "one.pcap"
    path.write_bytes(_pcap(POLLS + [(1_000_000, REQUEST), (until, b"")]))
    last = (UNANSWERED if unanswered else WITHIN).replace("     3 ", "    21 ")
    assert _decode([str(path)], monkeypatch, pure)[-1] == last
    assert _decode([str(path), "-Y", "unanswered"], monkeypatch, pure) == ([last] if unanswered else [])
