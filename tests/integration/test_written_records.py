"""What `-w` writes decodes back to the same items, in the engine, in VW3_PURE_PYTHON=1 and in the plugin.

A reader takes a record's end for a pause of the line: evidence that a frame ends there (framing/rtu.py
_followed). The writer wrote every noise run as a record of its own, so a record ended where the line had
given no such evidence, and the stream read back made a frame of a CRC-valid tail of a noise run, or of
a damaged frame ending where the noise did (7 of 30 damaged streams in a review). A noise run now shares
the record of the damaged frame or noise after it (render/capturefile.py CaptureOutput.write_items); an
intact frame is still a record of its own, as Wireshark's mbrtu reads them. A noise run ending the input that
alone would be a frame by its shape goes at the end of the record before it (CaptureOutput.release): the
input's end says little of a frame, a record's start and end would bound one.
"""
from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_compare import compare
from lua_harness import ensure_tool, lua_items, python_items, record_lengths

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))

from noise_accuracy import damage, session  # noqa: E402

# The review's stream: one garbage byte, a response to slave 3 (FC23, CRC valid), a damaged exception,
# an intact request. Decoded, the first 8 bytes are noise: nothing confirms the response there.
REVIEW = "d1 03 17 02 00 00 c4 74 01 e9 bb b8 2b 0c 10 0c 82 00 01 02 00 64 2d 09"
REVIEW_LINES = [
    "     1            -   - noise     8 bytes of noise at offset 0: d1 03 17 02 00 00 c4 74",
    "     2            -   1 exception User-defined function 105: exception 187 (Unknown exception 187) "
    "[no request] [response without a matching request in the capture] "
    "[warning: exception code 187 is not defined by the spec]  CRC BAD (received 0x2BB8, expected 0xE32F)",
    "     3            -  12 request   Write Multiple Registers 3202: 3202=100 "
    "[the capture ends before any response: not known whether it was answered]  CRC ok",
]
# The end of damaged_stream(101): an intact FC11 request to slave 205, then 24 bytes shaped as a damaged FC21
# request to slave 28 (byte count 0x13: 24 bytes, CRC bad) that the input's end does not confirm (not the
# answer awaited). A record of its own, its start and end bounded it: read back, 'Write File Record ... CRC BAD'.
TAIL = "cd 0b 14 e7 1c 15 13 06 00 08 04 b4 00 04 1f d3 94 25 86 08 35 78 68 4f b0 b6 09 b2"
TAIL_LINES = [
    "     1            - 205 request   Get Comm Event Counter "
    "[the capture ends before any response: not known whether it was answered]  CRC ok",
    "     2            -   - noise     24 bytes of noise at offset 4: 1c 15 13 06 00 08 04 b4 00 04 1f d3 94 25 86 08…",
]
# damaged_stream(3051): a noise run whose first bytes read as slave 41's user-defined function 70 (a CRC scan, no
# length rule), then an intact FC43 request. Written as two records, the scan from the noise record's start
# checked 85 bytes by chance, across the request's record: read back as 'User-defined function 70 81 bytes of
# data'. A CRC scan stops at a record that is a frame of its own (framing/reach.py _framed_reach).
SCANNED = [
    "    16            -   - noise     78 bytes of noise at offset 697: "
    "29 46 3c 0d aa 3b e5 7f 07 98 93 c7 7e 4c b5 b1…",
    "    17            - 175 request   Encapsulated Interface Transport Read Device Identification, basic, "
    "from object 0 [no response]  CRC ok",
]
MBRTU = ["-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""', "-o", "mbrtu.crc_verification:TRUE"]


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert status == 0, err
    return out


def damaged_stream(seed: int) -> bytes:
    """A bus session of 12 transactions to random slaves, 40 % of its frames damaged (flipped bits,
    dropped bytes, inserted garbage, truncation: bench/noise_accuracy.py), seeded."""
    rng = random.Random(seed)
    frames = session(rng, 12)
    return b"".join(damage(rng, frame)[1] if rng.random() < 0.4 else frame for frame in frames)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_the_review_stream_decodes_back_to_the_same_items(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    written = tmp_path / "review.pcap"
    assert _decode(["--hex", REVIEW], monkeypatch, pure).splitlines() == REVIEW_LINES
    assert _decode(["--hex", REVIEW, "-w", str(written)], monkeypatch, pure) == ""
    # The noise run and the damaged exception after it are one record; the intact request is its own.
    assert record_lengths(written) == [13, 11]
    assert _decode([str(written)], monkeypatch, pure).splitlines() == REVIEW_LINES


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_a_noise_run_ending_the_input_shaped_as_a_frame_shares_the_record_before_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    written, comments = tmp_path / "tail.pcap", tmp_path / "tail.pcapng"
    assert _decode(["--hex", TAIL], monkeypatch, pure).splitlines() == TAIL_LINES
    for path in (written, comments):
        assert _decode(["--hex", TAIL, "-w", str(path)], monkeypatch, pure) == ""
        assert _decode([str(path)], monkeypatch, pure).splitlines() == TAIL_LINES
    assert record_lengths(written) == [28]
    # A noise run that is no frame by its shape keeps its record: the request alone, then the noise.
    shorter = _decode(["--hex", TAIL[:-6]], monkeypatch, pure)
    assert _decode(["--hex", TAIL[:-6], "-w", str(written)], monkeypatch, pure) == ""
    assert record_lengths(written) == [4, 22]
    assert _decode([str(written)], monkeypatch, pure) == shorter


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_a_crc_scan_does_not_reach_across_a_record_that_is_a_frame(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    raw, written = tmp_path / "stream.bin", tmp_path / "stream.pcap"
    raw.write_bytes(damaged_stream(3051))
    items, lines = _items([str(raw), "--format", "raw"], monkeypatch, pure)
    assert lines.splitlines()[15:17] == SCANNED
    assert _decode([str(raw), "--format", "raw", "-w", str(written)], monkeypatch, pure) == ""
    assert record_lengths(written)[13:15] == [78, 7]  # (the noise run, then the request)
    assert _items([str(written)], monkeypatch, pure) == (items, lines)


def _items(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> tuple[list[dict], str]:
    lines = _decode([*argv, "--json"], monkeypatch, pure)
    return [json.loads(line) for line in lines.splitlines()], _decode(argv, monkeypatch, pure)


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_damaged_streams_decode_back_to_the_same_items(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    raw, written = tmp_path / "stream.bin", tmp_path / "stream.pcap"
    changed = 0
    for seed in range(40):
        raw.write_bytes(damaged_stream(seed))
        items, lines = _items([str(raw), "--format", "raw"], monkeypatch, pure)
        assert _decode([str(raw), "--format", "raw", "-w", str(written)], monkeypatch, pure) == ""
        # (a raw stream has no times: the records are at the epoch, read back as untimed)
        assert _items([str(written)], monkeypatch, pure) == (items, lines), seed
        changed += len(record_lengths(written)) < len(items)
    assert changed >= 10  # streams where a noise run shares a record: what the property is about


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_a_long_garbage_run_decodes_back_the_same_in_records_of_snaplen_at_most(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    raw, written = tmp_path / "garbage.bin", tmp_path / "garbage.pcap"
    for seed in range(2):
        rng = random.Random(seed)
        raw.write_bytes(damaged_stream(seed)[:60] + rng.randbytes(150_000) + damaged_stream(seed + 100))
        items, lines = _items([str(raw), "--format", "raw"], monkeypatch, pure)
        _decode([str(raw), "--format", "raw", "-w", str(written)], monkeypatch, pure)
        assert _items([str(written)], monkeypatch, pure) == (items, lines), seed
        assert max(record_lengths(written)) <= 65535  # the file header's snaplen


def test_the_plugin_reads_the_written_records_as_vw3_decode(tmp_path: Path) -> None:
    ensure_tool("tshark", "tshark")
    raw = tmp_path / "stream.bin"
    # The review's stream, and damaged streams that decoded back otherwise before (a CRC-valid tail of a
    # noise run, a damaged frame ending where a noise run did).
    # Then streams ending in noise shaped as a frame (101 ends in TAIL), written in the record before it.
    streams = [bytes.fromhex(REVIEW), *(damaged_stream(seed) for seed in (1, 3, 10, 17, 101, 322))]
    for number, data in enumerate(streams):
        raw.write_bytes(data)
        written = tmp_path / f"written{number}.pcap"
        assert run_cli([str(raw), "--format", "raw", "-w", str(written)])[0] == 0
        original = [json.loads(line) for line in run_cli([str(raw), "--format", "raw", "--json"])[1].splitlines()]
        python = python_items(written, [])
        assert [item.data for item in python if item.data["kind"] != "noise"] == [
            item for item in original if item["kind"] != "noise"]
        differences = compare(python, lua_items(written)[0])
        assert not differences, "\n".join(differences[:40])


def test_mbrtu_still_sees_each_intact_frame_as_a_record_of_its_own(tmp_path: Path) -> None:
    tshark = ensure_tool("tshark", "tshark")
    written, comments = tmp_path / "review.pcap", tmp_path / "review.pcapng"
    assert run_cli(["--hex", REVIEW, "-w", str(written)])[0] == 0
    assert run_cli(["--hex", REVIEW, "-w", str(comments)])[0] == 0
    fields = ["-T", "fields", "-E", "separator=|", "-e", "frame.len", "-e", "mbrtu.unit_id", "-e",
              "modbus.func_code", "-e", "mbrtu.crc16.status", "-e", "frame.comment"]
    for path in (written, comments):
        result = subprocess.run([tshark, "-r", str(path), *MBRTU, *fields], capture_output=True, text=True,
                                timeout=300)
        assert result.returncode == 0, result.stderr
        rows = [line.split("|") for line in result.stdout.splitlines()]
        assert [row[:4] for row in rows] == [["13", "209", "", ""], ["11", "12", "16", "1"]]
    assert rows[0][4] == "noise: 8 bytes, no valid frame; then a damaged frame (5 bytes)"
