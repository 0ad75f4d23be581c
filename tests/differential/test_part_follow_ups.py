"""Records captured in part (`editcap -s N`), followed up: the answer of a request captured in part answers it
(not `[no response]`, not "no reply" in --stats), -w writes such a record with both its lengths, a capture of
nothing but such records is said so, a record of which no byte was captured is a cut, one longer than a chunk is
one item, and --stats counts them apart. Python stages and the compiled engine alike (byte-identical)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import engine_output_as_python
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
