"""The plugin on timed captures of a request or an answer a silence cuts (tests/differential/test_silence_cut.py,
test_silence_cut_files.py): it says what live and vw3-decode say, 'a silence cuts a request (4 of 8 bytes)' (it said
'no valid frame', and 'the capture ends inside a request (3 of 8 bytes)' for bytes a silence cut before the file's
end: silence_cut in lua/src/rtu.lua); the cut at the file's end keeps its reason. Exact fields (tshark -2), the
tree's lines, and every field as vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.function", "-e", "vw3.noise.reason"]


def test_a_request_a_silence_cuts(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "silence.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (POLL[:4], T0 + 1.0),
                                                  (POLL, T0 + 2.0), (ANSWER, T0 + 2.01), (POLL[:4], T0 + 3.0)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;3;", "2;3;", "4;;a silence cuts a request (4 of 8 bytes)", "1;3;", "2;3;",
        "4;;the capture ends inside a request (4 of 8 bytes)"]
    tree = run_tshark(pcap, "-V", "-Y", "frame.number == 3").stdout.splitlines()
    at = tree.index("VW3 noise, 4 bytes: a silence cuts a request (4 of 8 bytes)")
    assert tree[at + 4] == "    [Why noise: a silence cuts a request (4 of 8 bytes)]"
    assert_same_as_vw3_decode(pcap)


def test_an_answer_a_silence_cuts(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "answer.pcap", [(POLL, T0), (ANSWER[:5], T0 + 0.01), (POLL, T0 + 1.0),
                                                 (ANSWER, T0 + 1.01)])
    assert tshark_fields(pcap, FIELDS) == ["1;3;", "4;;a silence cuts the response (5 of 9 bytes)", "1;3;", "2;3;"]
    assert_same_as_vw3_decode(pcap)


def test_a_silence_before_the_end_of_the_capture(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "end.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (POLL[:2], T0 + 1.0),
                                              (b"\x01", T0 + 2.0)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;3;", "2;3;", "4;;a silence cuts a request (2 of 8 bytes)", "4;;too short for a frame"]
    assert_same_as_vw3_decode(pcap)
