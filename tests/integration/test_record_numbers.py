"""-T fields -e record: the number of the capture record holding an item's last byte, tshark's frame.number of the
packet where Wireshark shows it (the plugin shows a frame split over records in the record completing it; its
request_frame and response_frame name that record). vw3-decode numbers its items (frames and noise runs) on
their own, so after a record of no byte (an RTAC event, an empty record), a frame split over records, or another
interface's packets, its item N is not Wireshark's frame N: `record` is, for every pcap and pcapng record (empty
ones and other interfaces' counted), through a ring buffer's files (numbered on, as their mergecap -a), in the
engine's bulk read and the Python reader alike; -Y tests it. Before, `-e record` was refused (`not a field`) and
nothing gave Wireshark's number. (The key is data/fields.toml's: /work/patches/wire69-record-field.diff.)"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from helpers import run_cli, use_engine
from lua_harness import ensure_tool

from dissector.model import Stamp
from dissector.render.pcapwriter import PcapWriter

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_empty_records_inside import capture  # noqa: E402
from test_rtac_packet_times import ANSWER, REQUEST, _pcapng  # noqa: E402

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1_767_225_600_000_000  # us


def _fields(path: Path | list[str], *keys: str) -> list[str]:
    files = [str(path)] if isinstance(path, Path) else path
    status, out, err = run_cli(["-n", "-T", "fields", *(part for key in keys for part in ("-e", key)), *files])
    assert status == 0, err
    return out.splitlines()


def _tshark(path: Path, *options: str) -> list[str]:
    done = subprocess.run([ensure_tool("tshark", "tshark"), "-n", "-r", str(path), "-T", "fields", *options],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


@BOTH
@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_empty_records_and_split_frames(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                        suffix: str) -> None:
    """test_empty_records_inside.py's capture: records 2, 4, 6, 10, 11 empty, a request split over 5 and 7 (the
    plugin shows it in 7, its answer's request_frame: test_empty_records_inside.py)."""
    use_engine(monkeypatch, pure)
    path = capture(tmp_path, suffix)
    assert _fields(path, "frame", "record", "kind") == [
        "1\t1\trequest", "2\t3\tresponse", "3\t7\trequest", "4\t8\tresponse", "5\t9\trequest"]
    assert _tshark(path, "-e", "frame.number", "-e", "frame.len")[:9:2] == ["1\t8", "3\t9", "5\t4", "7\t4", "9\t8"]
    status, out, err = run_cli(["-n", "-Y", "record >= 8", str(path)])  # (-Y record: Wireshark's packet 8 on)
    assert (status, [line.split()[0] for line in out.splitlines()], err) == (0, ["4", "5"], "")


@BOTH
def test_the_engines_bulk_read_numbers_every_record(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    pure: bool) -> None:
    """A pcap of 3000 polls, an empty record after every seventh request: read in bulk by the engine (scan_pcap)."""
    use_engine(monkeypatch, pure)
    path = tmp_path / "big.pcap"
    with path.open("wb") as stream:
        writer, micros = PcapWriter(stream, flush=False), 0
        for poll in range(3000):
            writer.write(REQUEST, Stamp((T0 + micros) * 1000))
            if poll % 7 == 0:
                writer.write(b"", Stamp((T0 + micros + 1000) * 1000))
            writer.write(ANSWER, Stamp((T0 + micros + 6000) * 1000))
            micros += 101_000
    numbers = [line.split("\t")[1] for line in _fields(path, "frame", "record")]
    theirs = [number for number, length in (line.split("\t") for line in _tshark(path, "-e", "frame.number", "-e",
                                                                                   "frame.len")) if length != "0"]
    assert numbers == theirs and numbers[-2:] == ["6428", "6429"]


@BOTH
def test_several_interfaces_and_a_ring(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    two = _pcapng(tmp_path / "two.pcapng", [147, 147], [
        (0, 0, REQUEST), (1, 1000, REQUEST), (0, 5000, ANSWER), (1, 6000, ANSWER), (0, 9000, b""),
        (1, 100_000, REQUEST), (0, 100_500, REQUEST)])
    assert _fields(two, "record", "kind") == ["1\trequest", "3\tresponse", "7\trequest",  # (interface 0's bus)
                                              "2\trequest", "4\tresponse", "6\trequest"]
    ring = tmp_path / "ring"
    ring.mkdir()
    files = []
    for number, start in ((1, 0), (2, 1_000_000)):
        files.append(str(_pcapng(ring / f"bus_0000{number}_2026010100000{number}.pcapng", [147],
                                 [(0, start, REQUEST), (0, start + 1000, b""), (0, start + 5000, ANSWER)])))
    assert _fields(files, "frame", "record") == ["1\t1", "2\t3", "3\t4", "4\t6"]


def test_other_inputs_have_none(tmp_path: Path) -> None:
    assert run_cli(["-T", "fields", "-e", "frame", "-e", "record", "--hex", "0C 03 20 D0 00 03 0E EF"]) == (
        0, "1\t\n", "")


@BOTH
def test_a_ring_of_pcaps_read_in_bulk(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    """Each file of a pcap ring read in bulk by the engine numbers on from the files before (it began at 1 again)."""
    use_engine(monkeypatch, pure)
    files, micros = [], 0
    for number in (1, 2):
        path = tmp_path / f"bus_0000{number}_2026010100000{number}.pcap"
        with path.open("wb") as stream:
            writer = PcapWriter(stream, flush=False)
            for _poll in range(1000):
                writer.write(REQUEST, Stamp((T0 + micros) * 1000))
                writer.write(ANSWER, Stamp((T0 + micros + 5000) * 1000))
                micros += 100_000
        files.append(str(path))
    lines = _fields(files, "frame", "record")
    assert len(lines) == 4000 and all(line.split("\t")[0] == line.split("\t")[1] for line in lines), \
        [line for line in lines if line.split("\t")[0] != line.split("\t")[1]][:3]
