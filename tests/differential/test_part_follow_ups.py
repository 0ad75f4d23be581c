"""Records captured in part (`editcap -s N`), followed up: the answer of a request captured in part answers it
(not `[no response]`, not "no reply" in --stats), -w writes such a record with both its lengths, a capture of
nothing but such records is said so, a record of which no byte was captured is a cut, one longer than a chunk is
one item, and --stats counts them apart. Python stages and the compiled engine alike (byte-identical)."""
from __future__ import annotations

import json
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from helpers import engine_output_as_python, pcapng_packets
from part_records import ANSWER, REQUEST, WRITE, raw_pcap, two_cut

PAIRED = "captured in part (5 of its 9 bytes; slave 2, function 3; the answer to #1): its CRC cannot be checked"


def test_answer_captured_in_part_answers_its_request(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: line 1 ended `[no response]` and --stats counted the read 1 'no reply', though the slave answered
    (its answer's bytes cut by the snapshot length); the cut item did not name the request."""
    out, _framed = engine_output_as_python([str(two_cut(tmp_path))], monkeypatch)
    assert out.splitlines()[:2] == [
        "     1     0.000000   2 request   Read Holding Registers 8401..8402 (2) [answer captured in part in #2]  CRC ok",
        f"     2     0.010000   - noise     5 bytes of noise at offset 8: 02 03 04 00 03 [{PAIRED}]",
    ]
    out, _framed = engine_output_as_python([str(two_cut(tmp_path)), "--stats"], monkeypatch)
    lines = out.splitlines()
    assert "    2  3 Read Holding Registers    2     1                     0        0" in lines
    assert "    2  6 Write Single Register     1     0                     1        0" in lines


def test_answer_of_another_slave_or_too_late_is_not_paired(tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """A cut record of another slave, or past the timeout, answers nothing: the request stays unanswered."""
    other = bytes([3]) + ANSWER[1:5]
    capture = raw_pcap(tmp_path / "other.pcap", [(0, 8, REQUEST), (10_000, 9, other),
                                                  (100_000, 8, REQUEST), (1_200_000, 9, ANSWER[:5])])
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    lines = out.splitlines()
    assert lines[0].endswith("(2) [no response]  CRC ok")
    assert lines[1].endswith("[captured in part (5 of its 9 bytes; slave 3, function 3): its CRC cannot be checked]")
    assert lines[2].endswith("(2) [no response]  CRC ok")
    assert lines[3].endswith("[captured in part (5 of its 9 bytes; slave 2, function 3): its CRC cannot be checked]")


def test_exception_captured_in_part_answers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An exception (function 0x86) captured in part answers the write it refuses."""
    capture = raw_pcap(tmp_path / "exception.pcap", [(0, 8, WRITE), (10_000, 5, bytes([2, 0x86, 2]))])
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines()[:2] == [
        "     1     0.000000   2 request   Write Single Register 8401 = 1 [answer captured in part in #2]  CRC ok",
        "     2     0.010000   - noise     3 bytes of noise at offset 8: 02 86 02 [captured in part (3 of its 5 bytes;"
        " slave 2, function 134; the answer to #1): its CRC cannot be checked]",
    ]


def pcap_lengths(path: Path) -> list[tuple[int, int]]:
    """(captured, original) lengths of every record of a little-endian classic pcap."""
    data, position, found = path.read_bytes(), 24, []
    while position + 16 <= len(data):
        captured, original = struct.unpack_from("<II", data, position + 8)
        found.append((captured, original))
        position += 16 + captured
    return found


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_written_copy_keeps_records_captured_in_part(suffix: str, tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """-w writes a record captured in part with its captured and its original length, as editcap -s does, so
    the copy decodes as the capture. Before, written whole (5 of 5 bytes), the copy read back as a CRC BAD
    answer `8401=3 8402=518` and a noise byte 00; its pcapng copy also said vw3-decode's own noise comments were
    the input's packet comments."""
    capture, copy = two_cut(tmp_path), tmp_path / f"copy.{suffix}"
    original, _framed = engine_output_as_python([str(capture)], monkeypatch)
    written, _framed = engine_output_as_python([str(capture), "-w", str(copy)], monkeypatch)
    assert written == "".join(line + "\n" for line in original.splitlines() if line.startswith("vw3-decode: warning"))
    again, _framed = engine_output_as_python([str(copy)], monkeypatch)
    assert again == original
    if suffix == "pcap":
        assert pcap_lengths(copy) == [(8, 8), (5, 9), (5, 8), (8, 8), (8, 8), (9, 9)]
    else:
        assert [(len(raw), comments) for _time, raw, comments in pcapng_packets(copy, 0)][1:3] == [
            (5, [f"noise: 5 bytes, {PAIRED}"]),
            (5, ["noise: 5 bytes, captured in part (5 of its 8 bytes; slave 2, function 6): its CRC cannot be checked"])]


def test_a_capture_of_records_captured_in_part_is_said_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every record captured in part: the last warning says so. Before: "no valid Modbus RTU frame in 10 bytes
    (every item is noise or a frame with a bad check): not a Modbus capture, or another format or line speed?",
    sending the engineer after a format or a line speed when the snapshot length cut the frames."""
    capture = raw_pcap(tmp_path / "all.pcap", [(0, 8, REQUEST[:5]), (10_000, 9, ANSWER[:5])])
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines()[2:] == [
        "vw3-decode: warning: record 1: only 5 of its 8 bytes were captured",
        "vw3-decode: warning: record 2: only 5 of its 9 bytes were captured",
        f"vw3-decode: warning: {capture}: no frame can be checked: every record was captured in part (2 records, 10"
        " bytes: a snapshot length shorter than the frames), their CRCs cut off: capture again with a larger snapshot"
        " length",
    ]
    # (a capture with other noise besides is still asked about its format)
    mixed = raw_pcap(tmp_path / "mixed.pcap", [(0, 3, b"\xff\x00\x13"), (10_000, 9, ANSWER[:5])])
    out, _framed = engine_output_as_python([str(mixed)], monkeypatch)
    assert out.splitlines()[-1].startswith(f"vw3-decode: warning: {mixed}: no valid Modbus RTU frame in 8 bytes")


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_record_of_no_byte_captured_is_a_cut(suffix: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A record of which none of its 9 bytes were captured is a cut all the same (bytes were lost there): an
    item of no byte that says so, and the warning. Before: nothing at all between request 1 and the next. (Its 9
    bytes, within the timeout, are the read's answer's length: that answer, test_no_byte_answer.py.)"""
    capture = raw_pcap(tmp_path / "zero.pcap", [(0, 8, REQUEST), (10_000, 9, b""), (100_000, 8, REQUEST),
                                                 (110_000, 9, ANSWER)])
    if suffix == "pcapng":
        capture = as_pcapng(capture, tmp_path)
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines() == [
        "     1     0.000000   2 request   Read Holding Registers 8401..8402 (2) [answer captured in part in #2]  CRC ok",
        "     2     0.010000   - noise     0 bytes of noise at offset 8 [captured in part (0 of its 9 bytes; the answer to"
        " #1): its CRC cannot be checked]",
        "     3     0.100000   2 request   Read Holding Registers 8401..8402 (2)  CRC ok",
        "     4     0.110000   2 response  Read Holding Registers 8401..8402 (2): 8401=3 8402=2 [#3, 10.0 ms]  CRC ok",
        "vw3-decode: warning: record 2: only 0 of its 9 bytes were captured",
    ]
    # (nothing else: said as a capture of nothing but records captured in part)
    alone = raw_pcap(tmp_path / "alone.pcap", [(0, 9, b"")])
    out, _framed = engine_output_as_python([str(alone)], monkeypatch)
    assert out.splitlines()[-1] == (
        f"vw3-decode: warning: {alone}: no frame can be checked: every record was captured in part (1 record, 0 bytes:"
        " a snapshot length shorter than the frames), their CRCs cut off: capture again with a larger snapshot length")


def as_pcapng(capture: Path, tmp_path: Path) -> Path:
    """The capture as editcap writes it in pcapng (each record's lengths kept)."""
    if shutil.which("editcap") is None:
        pytest.skip("editcap (Wireshark) is not installed")
    copy = tmp_path / f"{capture.stem}.pcapng"
    subprocess.run(["editcap", "-F", "pcapng", str(capture), str(copy)], check=True, capture_output=True)
    return copy


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_record_captured_in_part_longer_than_a_chunk(suffix: str, tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """A record captured in part longer than a chunk (64 KiB): all its 70,000 bytes are the one item (and the
    answer to the request). Before: its first 65,536 bytes were framed as any (16 noise items of 4,096 bytes),
    only its last 4,464 bytes the item."""
    long = ANSWER[:2] + bytes(69_998)
    capture = raw_pcap(tmp_path / "long.pcap", [(0, 8, REQUEST), (10_000, 80_000, long), (200_000, 8, REQUEST),
                                                 (210_000, 9, ANSWER)], snaplen=262_144)
    if suffix == "pcapng":
        capture = as_pcapng(capture, tmp_path)
    out, _framed = engine_output_as_python([str(capture), "-T", "fields", "-e", "frame", "-e", "kind", "-e", "length",
                                            "-e", "reason"], monkeypatch)
    assert out.splitlines() == [
        "1\trequest\t8\t",
        "2\tnoise\t70000\tcaptured in part (70000 of its 80000 bytes; slave 2, function 3; the answer to #1): its CRC"
        " cannot be checked",
        "3\trequest\t8\t", "4\tresponse\t9\t",
        "vw3-decode: warning: record 2: only 70000 of its 80000 bytes were captured",
    ]


def test_stats_count_records_captured_in_part_apart(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """--stats counts records captured in part apart from line noise (a snapshot length cut them). Before: '4 frames,
    10 noise bytes in 2 runs', as if the line were noisy."""
    mixed = raw_pcap(tmp_path / "mixed.pcap", [(0, 3, b"\xff\x00\x13"), (10_000, 8, REQUEST), (20_000, 9, ANSWER[:5]),
                                                (100_000, 8, WRITE[:5])])
    out, _framed = engine_output_as_python([str(mixed), "--stats"], monkeypatch)
    assert out.splitlines()[0] == "1 frame, 3 noise bytes in 1 run, 2 records captured in part (10 bytes)"
    out, _framed = engine_output_as_python([str(mixed), "--stats", "--json"], monkeypatch)
    report = json.loads(out.splitlines()[0])
    assert (report["noise"], report["captured_in_part"]) == ({"items": 1, "bytes": 3}, {"items": 2, "bytes": 10})
