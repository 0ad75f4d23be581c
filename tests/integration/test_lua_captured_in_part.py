"""The plugin cuts at a record captured in part (tvb:len() below tvb:reported_len(): `editcap -s 5`), as
vw3-decode does (framing/stream.py _cut_part): its captured bytes are one noise item whose reason says so,
none framed with the next record's, in tshark's one pass and with -2; real tshark against vw3-decode --json."""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from lua_compare import lua_kind, lua_shown
from lua_harness import ROOT, assert_as_vw3_decode_in_one_and_two_passes, lua_items, python_items
from part_records import CUT_WRITE, PAIRED_ANSWER, raw_pcap, records_of, rtac_two_cut, two_cut

# (notes too: a request's `answer captured in part in #N`, which one pass cannot know when it shows the request)
LATER = frozenset(["response_frame", "unanswered", "notes"])


def reasons(pcap: Path, two_pass: bool = True) -> list[tuple[int, str, str]]:
    """(record, kind, reason) of every item the plugin shows."""
    items, _experts, _err = lua_items(pcap, two_pass=two_pass)
    return [(item.record, lua_kind(item) or "", item.fields.get("noise.reason", "")) for item in lua_shown(items)]


def test_two_records_captured_in_part(tmp_path: Path) -> None:
    """Before: the answer's 5 bytes and 4 of the write's were one response with a bad CRC, then a noise byte."""
    capture = two_cut(tmp_path)
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
    for two_pass in (True, False):
        assert reasons(capture, two_pass) == [
            (1, "request", ""), (2, "noise", PAIRED_ANSWER), (3, "noise", CUT_WRITE), (4, "request", ""),
            (5, "request", ""), (6, "response", "")]


def test_ascii_record_captured_in_part(tmp_path: Path) -> None:
    request, answer = b":020320010002D8\r\n", b":02030400030002F2\r\n"
    capture = raw_pcap(tmp_path / "ascii.pcap", [
        (0, len(request), request), (10_000, len(answer), answer[:7]), (100_000, len(request), request),
        (110_000, len(answer), answer)])
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
    assert reasons(capture)[1] == (
        2, "noise", "captured in part (7 of its 19 bytes; slave 2, function 3; the answer to #1): its LRC cannot be checked")


def test_a_record_that_checks_out_is_still_cut(tmp_path: Path) -> None:
    """A record captured in part whose bytes happen to be a frame with a good CRC (8 of a 9-byte record: a
    read request's shape) is no frame: its end is no frame's end, bytes were lost after it."""
    from helpers import rtu

    read, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    capture = raw_pcap(tmp_path / "lucky.pcap", [(0, 8, read), (10_000, 9, read), (100_000, 8, read),
                                                 (110_000, 9, answer)])
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
    assert reasons(capture) == [
        (1, "request", ""), (2, "noise", "captured in part (8 of its 9 bytes; slave 1, function 3; the answer to #1): its "
                                         "CRC cannot be checked"), (3, "request", ""), (4, "response", "")]


@pytest.mark.skipif(shutil.which("editcap") is None, reason="editcap (Wireshark) is not installed")
@pytest.mark.parametrize("snap", [5, 9])
def test_editcap_snapshot_of_a_real_capture(snap: int, tmp_path: Path) -> None:
    """`editcap -s N` of the ATV71 capture: the plugin's items are vw3-decode's, one a record."""
    capture = tmp_path / f"s{snap}.pcap"
    subprocess.run(["editcap", "-F", "pcap", "-s", str(snap), str(ROOT / "captures" / "atv71_commissioning.pcap"), str(capture)],
                   check=True, capture_output=True)
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
    shown = reasons(capture)
    assert len(shown) == 104
    cut = [reason for _record, kind, reason in shown if reason.startswith("captured in part")]
    python = [item.data.get("reason", "") for item in python_items(capture)]
    assert cut == [reason for reason in python if reason.startswith("captured in part")]
    assert len(cut) == sum(len(raw) > snap for raw in records_of(ROOT / "captures" / "atv71_commissioning.pcap"))


def test_rtac_record_captured_in_part(tmp_path: Path) -> None:
    """Through Wireshark's RTAC dissector (Decode As rtacser.data -> vw3): the tvb holds the serial bytes, its
    reported length theirs too, so the reason is vw3-decode's (5 of 9)."""
    items, _experts, _err = lua_items(rtac_two_cut(tmp_path), "-d", "rtacser.data,vw3", header=0)
    assert [(item.record, lua_kind(item), item.fields.get("noise.reason", "")) for item in lua_shown(items)] == [
        (1, "request", ""), (2, "noise", PAIRED_ANSWER), (3, "noise", CUT_WRITE), (4, "request", ""),
        (5, "request", ""), (6, "response", "")]


def test_info_marks_a_record_captured_in_part(tmp_path: Path) -> None:
    """The Info column marks it as tshark's mbrtu marks the packet (`[Packet size limited during capture]`) and
    vw3-decode's summary line does: the reason between brackets."""
    from lua_compare import tshark_fields

    rows = tshark_fields(two_cut(tmp_path), ["-T", "fields", "-e", "_ws.col.Info"])
    assert rows[1:3] == [f"noise (5 bytes) [{PAIRED_ANSWER}]", f"noise (5 bytes) [{CUT_WRITE}]"]


def test_request_whose_answer_is_captured_in_part(tmp_path: Path) -> None:
    """With -2 the request's expert note says its answer was captured in part (before: `Request not answered`,
    as if the slave had not answered); the cut item names the request."""
    from lua_compare import tshark_fields

    rows = tshark_fields(two_cut(tmp_path), ["-2", "-T", "fields", "-e", "_ws.col.Info", "-e", "_ws.expert.message"])
    assert rows[:2] == [
        "2 Read Holding Registers request 8401..8402 (2)\tanswer captured in part in #2",
        f"noise (5 bytes) [{PAIRED_ANSWER}]\t5 bytes outside any frame: {PAIRED_ANSWER}",
    ]


def test_record_of_no_byte_captured(tmp_path: Path) -> None:
    """A record of which none of its 9 bytes were captured is a cut in the plugin too: an item of no byte that
    says so (before: nothing shown for it), as vw3-decode in one pass and two; of the length of the read's answer,
    within the timeout, it is that answer (test_no_byte_answer.py)."""
    from helpers import rtu

    request, answer = rtu("02 03 20d1 0002"), rtu("02 03 04 0003 0002")
    capture = raw_pcap(tmp_path / "zero.pcap", [(0, 8, request), (10_000, 9, b""), (100_000, 8, request),
                                                 (110_000, 9, answer)])
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
    assert reasons(capture) == [
        (1, "request", ""),
        (2, "noise", "captured in part (0 of its 9 bytes; the answer to #1): its CRC cannot be checked"),
        (3, "request", ""), (4, "response", "")]
