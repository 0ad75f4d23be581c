"""A pcap/pcapng record captured in part (a snapshot length shorter than the frame: `editcap -s 5`, tshark's
`[Packet size limited during capture]`) is a cut: its captured bytes are one item that says so, never framed
with the next record's bytes (which made a CRC BAD frame and noise), and the next record frames from a clean
start. The same through the Python stages and the compiled engine (which hands such a record to them)."""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from helpers import engine_output_as_python, run_cli
from part_records import ANSWER, CAPTURES, CUT_ANSWER, CUT_WRITE, PAIRED_ANSWER, REQUEST, raw_pcap, records_of, rtac_two_cut, two_cut

TWO_CUT_LINES = [
    "     1     0.000000   2 request   Read Holding Registers 8401..8402 (2) [answer captured in part in #2]  CRC ok",
    f"     2     0.010000   - noise     5 bytes of noise at offset 8: 02 03 04 00 03 [{PAIRED_ANSWER}]",
    f"     3     0.100000   - noise     5 bytes of noise at offset 13: 02 06 20 d1 00 [{CUT_WRITE}]",
    "     4     0.110000   2 request   Write Single Register 8401 = 1 [no response]  CRC ok",
    "     5     0.200000   2 request   Read Holding Registers 8401..8402 (2)  CRC ok",
    "     6     0.210000   2 response  Read Holding Registers 8401..8402 (2): 8401=3 8402=2 [#5, 10.0 ms]  CRC ok",
]
WARNINGS = [
    "vw3-decode: warning: record 2: only 5 of its 9 bytes were captured",
    "vw3-decode: warning: record 3: only 5 of its 8 bytes were captured",
]


def test_records_captured_in_part_are_cut(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: the answer's 5 bytes and 4 of the write's made a CRC BAD answer with a made-up 8402=518 and a
    silence of 87 ms inside it, then a noise byte 00 (the summary's `CRC BAD (received 0xD120, expected
    0x51B8)`)."""
    capture = two_cut(tmp_path)
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines() == TWO_CUT_LINES + WARNINGS
    status, _out, _err = run_cli([str(capture)])
    assert status == 0


@pytest.mark.parametrize("option", [["-V"], ["--json"], ["-T", "fields", "-e", "frame", "-e", "kind", "-e", "reason"],
                                    ["--stats"], ["-x"], ["-Y", "kind == \"noise\""]])
def test_every_output_says_captured_in_part(option: list[str], tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    capture = two_cut(tmp_path)
    out, _framed = engine_output_as_python([str(capture), *option], monkeypatch)
    lines = out.splitlines()
    assert "CRC BAD" not in out and "CRC bad" not in out
    if option == ["-V"]:
        assert f"    Reason: {PAIRED_ANSWER}" in lines and f"    Reason: {CUT_WRITE}" in lines
        assert "CRC BAD" not in out
    elif option == ["--json"]:
        items = [json.loads(line) for line in lines if line.startswith("{")]
        assert [(item["kind"], item.get("reason")) for item in items] == [
            ("request", None), ("noise", PAIRED_ANSWER), ("noise", CUT_WRITE), ("request", None), ("request", None),
            ("response", None)]
        assert [item["raw"] for item in items[1:3]] == ["0203040003", "020620d100"]
    elif option[0] == "-T":
        assert lines[:6] == ["1\trequest\t", f"2\tnoise\t{PAIRED_ANSWER}", f"3\tnoise\t{CUT_WRITE}", "4\trequest\t",
                             "5\trequest\t", "6\tresponse\t"]
    elif option == ["--stats"]:
        assert lines[0] == "4 frames, 0 noise bytes in 0 runs, 2 records captured in part (10 bytes)"
    elif option == ["-Y", "kind == \"noise\""]:
        assert lines == TWO_CUT_LINES[1:3] + WARNINGS


def test_ascii_record_captured_in_part(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An ASCII line captured in part: its characters are one item, its LRC not checked; the slave and the
    function its hex digits give. Before: its 7 characters ran into the next line's as noise."""
    request, answer = b":020320010002D8\r\n", b":02030400030002F2\r\n"
    capture = raw_pcap(tmp_path / "ascii.pcap", [
        (0, len(request), request), (10_000, len(answer), answer[:7]), (100_000, len(request), request),
        (110_000, len(answer), answer)])
    out, _framed = engine_output_as_python([str(capture), "--mode", "ascii", "-V"], monkeypatch)
    assert ("    Reason: captured in part (7 of its 19 bytes; slave 2, function 3; the answer to #1): its LRC cannot be"
            " checked"
            in out.splitlines())
    out, _framed = engine_output_as_python([str(capture), "--mode", "ascii"], monkeypatch)
    assert out.splitlines()[:4] == [
        "     1     0.000000   2 request   Read Holding Registers 8193..8194 (2) [answer captured in part in #2]  LRC ok",
        "     2     0.010000   - noise     7 bytes of noise at offset 17: 3a 30 32 30 33 30 34 [captured in part (7 of"
        " its 19 bytes; slave 2, function 3; the answer to #1): its LRC cannot be checked]",
        "     3     0.100000   2 request   Read Holding Registers 8193..8194 (2)  LRC ok",
        "     4     0.110000   2 response  Read Holding Registers 8193..8194 (2): 8193=3 8194=2 [#3, 10.0 ms]  LRC ok",
    ]


@pytest.mark.skipif(shutil.which("editcap") is None, reason="editcap (Wireshark) is not installed")
@pytest.mark.parametrize("output", ["pcap", "pcapng"])
def test_editcap_snapshot_of_a_real_capture(output: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """`editcap -s 5` of the ATV71 capture's first 8 records: every record longer than 5 bytes is an item of
    its own, none framed with the next (before: record 6's `02 03 04 00 03` and 4 bytes of record 7 made a
    CRC BAD answer `8401=3 8402=518`, then a noise byte 00)."""
    capture = tmp_path / f"s5.{output}"
    subprocess.run(["editcap", "-F", output, "-r", "-s", "5", str(CAPTURES / "atv71_commissioning.pcap"),
                    str(capture), "1-8"], check=True, capture_output=True)
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    lines = out.splitlines()
    assert [line[: line.index(" [")] for line in lines[:8]] == [
        "     1     0.000000   - noise     5 bytes of noise at offset 0: 02 2b 0e 01 00",
        "     2     0.010730   - noise     5 bytes of noise at offset 5: 02 2b 0e 01 02",
        "     3     0.046307   - noise     5 bytes of noise at offset 10: 02 03 0c 1e 00",
        "     4     0.059787   - noise     5 bytes of noise at offset 15: 02 03 08 00 28",
        "     5     0.077811   - noise     5 bytes of noise at offset 20: 02 03 20 d1 00",
        "     6     0.091388   - noise     5 bytes of noise at offset 25: 02 03 04 00 03",
        "     7     0.102650   - noise     5 bytes of noise at offset 30: 02 06 20 d1 00",
        "     8     0.111429   - noise     5 bytes of noise at offset 35: 02 06 20 d1 00",
    ]
    assert all(line.endswith(": its CRC cannot be checked]") for line in lines[:8])
    reasons = [line[len("    Reason: "):] for line in engine_output_as_python([str(capture), "-V"], monkeypatch)[0]
               .splitlines() if line.startswith("    Reason: ")]
    assert reasons == [
        "captured in part (5 of its 7 bytes; slave 2, function 43): its CRC cannot be checked",
        "captured in part (5 of its 55 bytes; slave 2, function 43): its CRC cannot be checked",
        "captured in part (5 of its 8 bytes; slave 2, function 3): its CRC cannot be checked",
        "captured in part (5 of its 13 bytes; slave 2, function 3): its CRC cannot be checked",
        "captured in part (5 of its 8 bytes; slave 2, function 3): its CRC cannot be checked",
        "captured in part (5 of its 9 bytes; slave 2, function 3): its CRC cannot be checked",
        "captured in part (5 of its 8 bytes; slave 2, function 6): its CRC cannot be checked",
        "captured in part (5 of its 8 bytes; slave 2, function 6): its CRC cannot be checked",
    ]


@pytest.mark.skipif(shutil.which("editcap") is None, reason="editcap (Wireshark) is not installed")
def test_editcap_snapshot_keeps_the_whole_records(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """`editcap -s 9` of the whole ATV71 capture: records of 9 bytes or fewer stay whole frames, each longer
    one is its 9 bytes; every byte is in one item, and no frame has a bad CRC."""
    capture = tmp_path / "s9.pcap"
    subprocess.run(["editcap", "-s", "9", str(CAPTURES / "atv71_commissioning.pcap"), str(capture)], check=True,
                   capture_output=True)
    out, _framed = engine_output_as_python([str(capture), "--json"], monkeypatch)
    items = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    assert len(items) == 104  # (one a record)
    records = records_of(CAPTURES / "atv71_commissioning.pcap")
    assert sum(item["length"] for item in items) == sum(min(9, len(raw)) for raw in records)
    assert all(item["crc_ok"] for item in items if item["kind"] != "noise")
    cut = [item for item in items if item["kind"] == "noise"]
    assert len(cut) == 43 and all(item["reason"].startswith("captured in part (9 of its ") for item in cut)


@pytest.mark.parametrize("block_bytes", [1, 1 << 18])
@pytest.mark.parametrize("read_bytes", [37, 1 << 20])
def test_engine_hands_a_cut_record_over(block_bytes: int, read_bytes: int, tmp_path: Path,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """Transactions the engine frames in bulk, then a record captured in part (the Python stages take the
    stream there, or inside it: StreamFramer.take_over), then more: the same lines either way."""
    from dissector.accel import records as bulk

    monkeypatch.setattr(bulk, "READ_BYTES", read_bytes)
    monkeypatch.setattr(bulk, "BLOCK_BYTES", block_bytes)
    records = []
    for k in range(20):
        records += [(k * 100_000, 8, REQUEST), (k * 100_000 + 10_000, 9, ANSWER)]
    records[21:22] = [(1_010_000, 9, ANSWER[:6])]  # the 11th answer captured in part
    records += [(2_000_000, 8, REQUEST[:3]), (2_010_000, 9, ANSWER)]  # a request captured in part
    capture = raw_pcap(tmp_path / "bulk.pcap", records)
    out, framed = engine_output_as_python([str(capture), "-T", "fields", "-e", "frame", "-e", "kind",
                                           "-e", "reason"], monkeypatch)
    lines = out.splitlines()
    assert lines[20] == "21\trequest\t"
    assert lines[21] == ("22\tnoise\tcaptured in part (6 of its 9 bytes; slave 2, function 3; the answer to #21): its CRC"
                         " cannot be checked")
    assert lines[40:43] == ["41\tnoise\tcaptured in part (3 of its 8 bytes; slave 2, function 3): its CRC cannot be checked",
                            "42\tresponse\t", "vw3-decode: warning: record 22: only 6 of its 9 bytes were captured"]
    summary, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert "CRC BAD" not in summary


def test_a_paused_framer_cuts_without_losing_bytes() -> None:
    """A caller that takes frames one at a time (pause_at: the compiled path's hand-overs) feeding a record
    captured in part: the bytes before it are framed, none lost under the pause (before the pause was lifted
    for the cut, the request's 8 bytes were dropped)."""
    from dissector.framing.rtu import RtuFramer
    from dissector.model import Chunk
    from dissector.sources.common import PartChunk

    framer = RtuFramer()
    framer.pause_at(0)
    assert framer.feed(Chunk(REQUEST, 1.0, True)) == []
    items = framer.feed(PartChunk(ANSWER[:5], 1.01, True, 2, (), 5, 9))
    assert [(item.offset, item.raw) for item in items] == [(0, REQUEST), (8, ANSWER[:5])]
    assert items[1].reason == CUT_ANSWER


def test_rtac_record_captured_in_part(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An RTAC serial record captured in part: its reason counts its serial bytes (5 of 9), as the plugin's tvb
    holds them, not the record's with the 12-byte header the warning counts (17 of 21)."""
    out, _framed = engine_output_as_python([str(rtac_two_cut(tmp_path))], monkeypatch)
    assert out.splitlines() == TWO_CUT_LINES + [
        "vw3-decode: warning: record 2: only 17 of its 21 bytes were captured",
        "vw3-decode: warning: record 3: only 17 of its 20 bytes were captured",
    ]
    out, _framed = engine_output_as_python([str(rtac_two_cut(tmp_path)), "-V"], monkeypatch)
    assert [line for line in out.splitlines() if line.startswith("    Reason: ")] == [
        f"    Reason: {PAIRED_ANSWER}", f"    Reason: {CUT_WRITE}"]


@pytest.mark.skipif(shutil.which("editcap") is None, reason="editcap (Wireshark) is not installed")
def test_comment_on_a_record_captured_in_part(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A pcapng packet comment on a record captured in part stays on its item (before: lost)."""
    capture = tmp_path / "noted.pcapng"
    subprocess.run(["editcap", "-F", "pcapng", "-a", "2:a note on the cut answer", str(two_cut(tmp_path)),
                    str(capture)], check=True, capture_output=True)
    out, _framed = engine_output_as_python([str(capture), "--json"], monkeypatch)
    items = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    assert [item.get("comments") for item in items] == [None, ["a note on the cut answer"], None, None, None, None]
