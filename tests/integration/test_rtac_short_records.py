"""RTAC serial records whose bytes have no RTAC time, in every output (engine and VW3_PURE_PYTHON=1, pcap and
pcapng):

- a record shorter than the 12-byte RTAC header is a frame tshark shows undissected (Data, 5 bytes). Its bytes
  are a noise item at its record's time, shown, counted and written by -w. Before, they were not shown at all (a
  warning said `its bytes are not decoded`), and -w wrote an empty record in their place;
- a record whose header microseconds are corrupt has its bytes decoded untimed (test_rtac_odd_records.py); -w
  writes them at their record's time, tshark's frame time for them, as it writes such a record of no serial byte.
  Before, at the epoch: tshark showed the copy's frame 3 in 1970, 56 years before frame 2."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest
from helpers import run_cli, use_engine

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_rtac_odd_records import CORRUPT, _ng, _pcap, _tshark_fields  # noqa: E402

SHORT = bytes.fromhex("0102030405")
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
WRITERS = pytest.mark.parametrize("write", [_pcap, _ng], ids=["pcap", "pcapng"])
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWER = "12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3"
WARNING = ("vw3-decode: warning: record 3: 5 bytes, shorter than the 12-byte RTAC serial header; its bytes are "
           "noise\n")


@BOTH
@WRITERS
def test_a_short_records_bytes_are_noise_at_its_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                     write) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "short.cap", SHORT)
    status, out, err = run_cli([str(path)])
    assert (status, err) == (0, WARNING)
    assert out.splitlines() == [
        f"     1     0.001000  {READ}",
        "     2     0.003000   - noise     5 bytes of noise at offset 8: 01 02 03 04 05",
        f"     3     0.009000  {ANSWER} [#1, 8.0 ms]  CRC ok",
        f"     4     0.500000  {READ}",
        f"     5     0.520000  {ANSWER} [#4, 20.0 ms]  CRC ok"]
    fields = run_cli(["-T", "fields", "-e", "frame", "-e", "time_relative", "-e", "time_delta", "-e", "raw",
                      str(path)])[1]
    assert fields.splitlines()[1] == "2\t0.003000000\t0.002000000\t0102030405"
    stats = run_cli(["--stats", str(path)])[1]
    assert stats.splitlines()[0] == "4 frames, 5 noise bytes in 1 run"


@BOTH
@WRITERS
def test_a_copy_keeps_a_short_records_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                            write) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "short.cap", SHORT)
    copy = tmp_path / "copy.pcap"
    assert run_cli(["-n", "-q", "-w", str(copy), str(path)]) == (0, "", WARNING)
    fields = ["-T", "fields", "-e", "frame.number", "-e", "frame.time_epoch"]
    assert _tshark_fields(copy, fields) == _tshark_fields(path, fields)
    assert _tshark_fields(copy, ["-T", "fields", "-e", "frame.len", "-e", "data"]) == [
        "0\t", "8\t0c0320d000030eef", "5\t0102030405", "11\t0c0306000100020003a5e4", "8\t0c0320d000030eef",
        "11\t0c0306000100020003a5e4"]


@BOTH
@pytest.mark.parametrize("fmt", ["pcap", "pcapng"])
@WRITERS
def test_untimed_bytes_are_written_at_their_records_time(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         pure: bool, write, fmt: str) -> None:  # type: ignore[no-untyped-def]
    use_engine(monkeypatch, pure)
    path = write(tmp_path / "corrupt.cap", CORRUPT + b"\x0c")
    out = run_cli([str(path)])[1]
    assert out.splitlines()[1] == "     2            -   - noise     1 byte of noise at offset 8: 0c"
    copy = tmp_path / f"copy.{fmt}"
    assert run_cli(["-n", "-q", "-F", fmt, "-w", str(copy), str(path)])[0] == 0
    fields = ["-T", "fields", "-e", "frame.number", "-e", "frame.time_epoch"]
    assert _tshark_fields(copy, fields) == _tshark_fields(path, fields)
    assert _tshark_fields(copy, fields)[2] == "3\t1767225600.003000000"
    # (read back, the copy's record is timed: the noise at its packet's time, which -t d counted from already)
    assert run_cli(["-t", "d", str(copy)])[1].splitlines()[1:3] == [
        "     2     0.002000   - noise     1 byte of noise at offset 8: 0c",
        f"     3     0.006000  {ANSWER} [#1, 8.0 ms]  CRC ok"]
