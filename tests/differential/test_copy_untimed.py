"""`vw3-decode ... -w COPY` of untimed records in a timed decode: an untimed record is written at the epoch
(render/pcapwriter.py, pcapngwriter.py), as the readers take it back untimed (sources/pcap.py
EpochRecord), and a record beginning where a timed read began is at that read's time
(render/capturefile.py _piece). Before, an untimed record was written at the time of the record before it:
an untimed input after a timed one read back timed (its answers '0.0 ms' after their requests), and so
did the untimed records of a nanosecond capture stamped 0 here and there (10 of 10 random ones below
decoded otherwise from COPY: times where FILE had none, silences inside frames FILE did not have); and the
read a frame began inside, after an untimed record, was written untimed."""
from __future__ import annotations

import random
import struct
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from test_timed_summary import cut_records, frames_of, write_pcap

REQUEST, ANSWER = rtu("0C 03 20 D0 00 03"), rtu("0C 03 06 0001 0002 0003")
T0 = 1_767_225_600_123_456_789  # ns
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
SUFFIXES = pytest.mark.parametrize("suffix", [".pcap", ".pcapng"])
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWERED = "12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3"


def lines(*arguments: object) -> list[str]:
    status, out, err = run_cli([str(argument) for argument in arguments])
    assert (status, err) == (0, "")
    return out.splitlines()


def pcap_records(path: Path) -> list[tuple[int, bytes]]:
    """(ns, bytes) of each record of a nanosecond pcap."""
    data, position, found = path.read_bytes(), 24, []
    while position < len(data):
        seconds, fraction, captured, _original = struct.unpack_from("<IIII", data, position)
        found.append((seconds * 10**9 + fraction, data[position + 16 : position + 16 + captured]))
        position += 16 + captured
    return found


@BOTH
@SUFFIXES
def test_an_untimed_input_after_a_timed_one_stays_untimed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                          pure: bool, suffix: str) -> None:
    use_engine(monkeypatch, pure)
    timed, untimed = tmp_path / "timed.pcap", tmp_path / "untimed.txt"
    write_pcap(timed, [(REQUEST, T0), (ANSWER, T0 + 12_345_678)])
    untimed.write_text(f"{REQUEST.hex(' ')}\n{ANSWER.hex(' ')}\n")
    copy = tmp_path / f"copy{suffix}"
    assert lines(timed, untimed, "-w", copy) == []
    assert lines(copy) == [  # (before: 3 and 4 at 0.012346, the answer [#3, 0.0 ms])
        f"     1  0.000000000  {READ}", f"     2  0.012345678  {ANSWERED} [#1, 12.3 ms]  CRC ok",
        f"     3            -  {READ}", f"     4            -  {ANSWERED} [#3]  CRC ok"]
    if suffix == ".pcap":
        assert [ns for ns, _data in pcap_records(copy)] == [T0, T0 + 12_345_678, 0, 0]


@BOTH
def test_a_read_after_an_untimed_record_keeps_its_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       pure: bool) -> None:
    """A damaged frame from an untimed record into a timed read, the request after it in that read: the
    copy's record of the read (it begins with the damaged frame's end) was written untimed, the request and
    its answer then untimed too ('[#2]', no 20.0 ms)."""
    use_engine(monkeypatch, pure)
    original, copy = tmp_path / "file.pcap", tmp_path / "copy.pcap"
    write_pcap(original, [(b"\xdd\xab\xae", None), (b"\x94\x85" + REQUEST, T0), (ANSWER, T0 + 20_000_000)])
    decoded = lines(original)
    assert decoded[1:] == [f"     2  0.000000000  {READ}", f"     3  0.020000000  {ANSWERED} [#2, 20.0 ms]  CRC ok"]
    assert lines(original, "-w", copy) == []
    assert pcap_records(copy) == pcap_records(original)
    assert lines(copy) == decoded


@BOTH
@SUFFIXES
@pytest.mark.parametrize("seed", range(6))
def test_untimed_records_of_a_timed_capture_copy_as_they_decode(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                pure: bool, suffix: str, seed: int) -> None:
    """Records cut anywhere in a random bus's frames, 3 in 10 stamped 0 (untimed), in a nanosecond pcap."""
    use_engine(monkeypatch, pure)
    original, copy = tmp_path / "file.pcap", tmp_path / f"copy{suffix}"
    write_pcap(original, cut_records(random.Random(seed), frames_of(100 + seed, damaged=0.06)[:40], "untimed"))
    assert lines(original, "-w", copy) == []
    assert lines(copy) == lines(original)
