"""`vw3-decode FILE -w COPY` decodes as FILE (sources/trail.py, render/capturefile.py write_items): an item
is a record, except where FILE's time changes inside it: there it is written in the records it came in,
each at its time. Before, a frame read in two records 2 ms apart (a tap's two reads, a silence inside
the frame) was one record at its first byte's time: COPY lost the 'silence inside the frame' warning
(the first test's COPY lines failed, and the last test's). Records of one time inside a frame
stay one record (a frame a packet, as Wireshark's mbrtu reads them): the ordinary cases below are
unchanged, and summarized alike from FILE and COPY, by the engine and the Python stages."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from dissector.model import Stamp
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1_767_225_600_000_000  # us
SILENCE = ("[warning: silence of 1.791 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 "
           "baud)]")
# The request read in two pieces with 2 ms of silence between them; its answer 10 ms after it.
SPLIT = [(REQUEST[:4], 0), (REQUEST[4:], 4_083), (ANSWER, 12_000)]


def capture(path: Path, records: list[tuple[bytes, int]]) -> Path:
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False) if path.suffix == ".pcapng" else PcapWriter(stream, flush=False)
        for data, micros in records:
            writer.write(data, Stamp((T0 + micros) * 1000))
    return path


def pcap_records(path: Path) -> list[tuple[int, bytes]]:
    data, position, found = path.read_bytes(), 24, []
    while position < len(data):
        seconds, micros, captured, _original = struct.unpack_from("<IIII", data, position)
        found.append((seconds * 1_000_000 + micros - T0, data[position + 16 : position + 16 + captured]))
        position += 16 + captured
    return found


def lines(*arguments: object) -> list[str]:
    status, out, err = run_cli([str(argument) for argument in arguments])
    assert (status, err) == (0, "")
    return out.splitlines()


@BOTH
@pytest.mark.parametrize("suffix", [".pcap", ".pcapng"])
def test_a_silence_inside_a_frame_stays_in_the_copy(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                     suffix: str) -> None:
    use_engine(monkeypatch, pure)
    original = capture(tmp_path / f"split{suffix}", SPLIT)
    decoded = lines(original)
    assert decoded == [
        f"     1     0.000000  12 request   Read Holding Registers 8400..8402 (3) {SILENCE}  CRC ok",
        "     2     0.012000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 "
        "[#1, 12.0 ms]  CRC ok"]
    copy = tmp_path / "copy.pcap"
    assert lines(original, "-w", copy) == []
    assert pcap_records(copy) == [(0, REQUEST[:4]), (4_083, REQUEST[4:]), (12_000, ANSWER)]
    assert lines(copy) == decoded


ORDINARY = {
    "a frame a record": [(REQUEST, 0), (ANSWER, 12_000), (REQUEST, 1_000_000), (ANSWER, 1_012_000)],
    "a read of two frames": [(REQUEST + ANSWER, 0), (REQUEST, 1_000_000), (ANSWER, 1_012_000)],
    "a frame in two reads of one time": [(REQUEST[:4], 0), (REQUEST[4:], 0), (ANSWER, 12_000)],
    "noise before a frame": [(b"\xff\x00", 0), (REQUEST, 1_000), (ANSWER, 13_000)],
    "noise across two reads": [(REQUEST, 0), (b"\x01\x02", 100_000), (b"\x03", 200_000), (ANSWER, 300_000)],
}


@BOTH
@pytest.mark.parametrize("case", list(ORDINARY))
def test_ordinary_copies_decode_as_their_original(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                  case: str) -> None:
    use_engine(monkeypatch, pure)
    original = capture(tmp_path / "file.pcap", ORDINARY[case])
    for copy in (tmp_path / "copy.pcap", tmp_path / "copy.pcapng"):
        assert lines(original, "-w", copy) == []
        assert lines(copy) == lines(original)


def test_a_noise_run_across_two_reads_keeps_their_times(tmp_path: Path) -> None:
    """Its two reads 100 ms apart stay two records (the framer makes two noise runs of them)."""
    original = capture(tmp_path / "file.pcap", ORDINARY["noise across two reads"])
    copy = tmp_path / "copy.pcap"
    lines(original, "-w", copy)
    assert pcap_records(copy) == [(0, REQUEST), (100_000, b"\x01\x02"), (200_000, b"\x03"), (300_000, ANSWER)]


def test_a_filtered_ring_and_standard_input_copy(tmp_path: Path) -> None:
    """-Y, -b and standard input write the records of the items they keep as a copy of the file does."""
    original = capture(tmp_path / "split.pcap", [*SPLIT, (REQUEST, 2_500_000), (ANSWER, 2_512_000)])
    filtered = tmp_path / "requests.pcap"
    lines(original, "-Y", 'kind == "request"', "-w", filtered)
    assert pcap_records(filtered) == [  # (and the capture's end: app/inputs.py CopyEnd)
        (0, REQUEST[:4]), (4_083, REQUEST[4:]), (2_500_000, REQUEST), (2_512_000, b"")]
    ring = tmp_path / "ring.pcap"
    lines(original, "-w", ring, "-b", "duration:1")
    parts = sorted(tmp_path.glob("ring_*.pcap"))
    assert [pcap_records(part) for part in parts] == [
        [(0, REQUEST[:4]), (4_083, REQUEST[4:]), (12_000, ANSWER)], [(2_500_000, REQUEST), (2_512_000, ANSWER)]]
    piped = tmp_path / "piped.pcap"
    status, out, err = run_cli(["-", "-w", str(piped)], stdin=original.read_bytes())
    assert (status, out, err) == (0, "", "")
    assert pcap_records(piped) == pcap_records(original)


def test_a_ring_keeps_an_item_in_one_file(tmp_path: Path) -> None:
    """-b duration:0.002: the request's second read, 4 ms after its first, stays in the file its first is
    in (each file a valid capture of whole items); the answer opens the next."""
    original = capture(tmp_path / "split.pcap", SPLIT)
    lines(original, "-w", tmp_path / "ring.pcap", "-b", "duration:0.002")
    parts = sorted(tmp_path.glob("ring_*.pcap"))
    assert [pcap_records(part) for part in parts] == [[(0, REQUEST[:4]), (4_083, REQUEST[4:])], [(12_000, ANSWER)]]


@BOTH
def test_an_item_from_inside_a_read_takes_the_reads_start(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           pure: bool) -> None:
    """The answer begins inside the read of its request and goes on in a read 20 ms later. The reader
    measures a silence from a read's time and length: cut at the second read alone, the copy's first record
    of the answer (4 bytes at the read's time) made up a silence of 17.708 ms where FILE has 13.125 ms (the
    read's 12 bytes). Its first record now begins where the read began, the request in it: the copy's
    records are FILE's (before: one record an item, the silence lost)."""
    use_engine(monkeypatch, pure)
    original = capture(tmp_path / "file.pcap", [(REQUEST + ANSWER[:4], 0), (ANSWER[4:], 20_000)])
    response = "12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 [#1, 0.0 ms]"
    assert lines(original)[1] == (f"     2     0.000000  {response} [warning: silence of 13.125 ms inside the "
                                  "frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)]  CRC ok")
    copy = tmp_path / "copy.pcap"
    lines(original, "-w", copy)
    assert pcap_records(copy) == [(0, REQUEST + ANSWER[:4]), (20_000, ANSWER[4:])]
    assert lines(copy) == lines(original)
