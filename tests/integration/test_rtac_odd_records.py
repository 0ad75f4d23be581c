"""RTAC records tshark shows as frames though their RTAC header tells no time: one whose header microseconds are
corrupt (1 s or more) and one shorter than the 12-byte header. Each is a packet at its record's time, as tshark
counts it: the answer after it says -t d 0.006000 from it (tshark's frame.time_delta), where before it said
0.008000 from the request (neither was a packet). The corrupt record's own serial bytes stay untimed (its record's
clock may not be its header's: tests/unit/test_capture_stamps.py); the short one's bytes are noise
(tests/integration/test_rtac_short_records.py). A -w copy keeps each record, an RTAC event's and the corrupt one's
as empty records at their times. Engine and VW3_PURE_PYTHON=1, pcap and pcapng."""
from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import run_cli, use_engine
from lua_harness import ensure_tool

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "differential"))  # (collected alone: not on the path)
from test_rtac_packet_times import ANSWER, REQUEST, T0, _pcapng, _rtac  # noqa: E402
from test_several_interface_times import _tsharks  # noqa: E402

CORRUPT = struct.pack(">IIBBH", T0, 4_000_000_000, 0x01, 0, 0)  # an event record, its microseconds corrupt
SHORT = _rtac(3000, 0x01, b"")[:5]
# (us after T0, record bytes): an event, the request, the odd record, the answer, a second poll
RECORDS = [(0, _rtac(0, 0x01, b"")), (1000, _rtac(1000, 0, REQUEST)), (3000, None), (9000, _rtac(9000, 0, ANSWER)),
           (500_000, _rtac(500_000, 0, REQUEST)), (520_000, _rtac(520_000, 0, ANSWER))]
ITEM_FRAMES = ["2", "4", "5", "6"]


def _pcap(path: Path, odd: bytes) -> Path:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 250)
    for micros, payload in RECORDS:
        payload = odd if payload is None else payload
        seconds, fraction = divmod(T0 * 1_000_000 + micros, 1_000_000)
        out += struct.pack("<IIII", seconds, fraction, len(payload), len(payload)) + payload
    path.write_bytes(out)
    return path


def _ng(path: Path, odd: bytes) -> Path:
    return _pcapng(path, [250], [(0, micros, odd if payload is None else payload) for micros, payload in RECORDS])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("write", [_pcap, _ng], ids=["pcap", "pcapng"])
@pytest.mark.parametrize("odd", [CORRUPT], ids=["corrupt-microseconds"])  # (the short one's bytes: test_rtac_short_records.py)
def test_each_is_a_packet_at_its_record_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                             write, odd: bytes) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "odd.cap", odd)
    status, fields, err = run_cli(["-T", "fields", "-e", "frame", "-e", "time_relative", "-e", "time_delta", str(path)])
    assert status == 0 and err.count("record 3: ") == 1, err
    theirs = _tsharks(path)
    assert fields.splitlines() == [f"{item}\t{theirs[frame]}" for item, frame in enumerate(ITEM_FRAMES, 1)]
    assert fields.splitlines()[1] == "2\t0.009000000\t0.006000000"
    out = run_cli(["-t", "d", str(path)])[1]
    assert [line[6:19] for line in out.splitlines()] == ["     0.001000", "     0.006000", "     0.491000",
                                                         "     0.020000"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_the_corrupt_records_bytes_stay_untimed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _pcap(tmp_path / "odd.pcap", CORRUPT + b"\x0c")
    status, out, err = run_cli(["-t", "d", str(path)])
    assert status == 0 and err == ("vw3-decode: warning: record 3: RTAC microseconds 4000000000 are not below "
                                   "1000000: a corrupt time stamp? Its bytes are decoded untimed\n")
    assert [" ".join(line.split()[:4]) for line in out.splitlines()] == [
        "1 0.001000 12 request", "2 - - noise", "3 0.006000 12 response",
        "4 0.491000 12 request", "5 0.020000 12 response"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("write", [_pcap, _ng], ids=["pcap", "pcapng"])
@pytest.mark.parametrize("odd", [CORRUPT, SHORT], ids=["corrupt-microseconds", "short"])
def test_a_copy_keeps_every_packet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, write,  # type: ignore[no-untyped-def]
                                   odd: bytes) -> None:
    """-w writes the serial bytes (link type 147), each event record, and the odd one at its time (the corrupt one
    an empty record, the short one its 5 bytes): tshark numbers and times the copy's packets as the input's.
    Before, the copy held the 4 frames alone."""
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "odd.cap", odd)
    copy = tmp_path / "copy.pcap"
    assert run_cli(["-n", "-w", str(copy), "-q", str(path)])[0] == 0
    fields = ["-T", "fields", "-e", "frame.number", "-e", "frame.time_epoch"]
    assert _tshark_fields(copy, fields) == _tshark_fields(path, fields)
    assert [line.split("\t")[1] for line in _tshark_fields(copy, ["-T", "fields", "-e", "frame.len", "-e",
                                                                  "frame.cap_len"])] == ["0", "8", str(len(odd) % 12), "11", "8", "11"]


def _tshark_fields(path: Path, options: list[str]) -> list[str]:
    done = subprocess.run([ensure_tool("tshark", "tshark"), "-n", "-r", str(path), *options], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()
