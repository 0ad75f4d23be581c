"""A damaged frame alone between two silences (a request with a bit flipped, its CRC bad): the file of the reads
(pcap, pcapng, a hex dump with times) shows it as a damaged request, 'CRC BAD', the silence after it saying where
it ends (framing/rtu.py _followed: a silence is a boundary). Live closes the bytes at that silence
(StreamFramer.finish(silence=True)) and weighed them as at the end of the capture, which says little of a damaged
frame: '8 bytes of noise ... no valid frame'. Now live takes the silence it closes them at as the evidence the
file has (rtu.py _followed), and says what the file says. Exact summary lines of --live on tapes
of the reads, the engine's live path and VW3_PURE_PYTHON=1's, and the file's."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import rtu
from live_tape import tape_of
from test_silence_cut import live
from test_silence_cut_files import ENGINES, decode

POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
DAMAGED = bytes.fromhex("05 03 00 00 40 04 45 8d")  # (05 03 0000 0004, bit 6 of its quantity's high byte flipped)
T0 = 1_700_000_000 * 10**9
SHOWN = ("5 request   Read Holding Registers 0..16387 (16388) [no response] [warning: quantity 16388 outside the "
         "spec's 1..125]  CRC BAD (received 0x8D45, expected 0x4D74)")


@ENGINES
@pytest.mark.parametrize("after", [1.0, 2.0], ids=["answered-poll", "unanswered"])
def test_live_shows_the_damaged_request_as_the_file_does(after: float, pure: bool, tmp_path: Path) -> None:
    reads = [(POLL, 100.0), (ANSWER, 100.01), (DAMAGED, 100.5), (POLL, 100.0 + after), (ANSWER, 100.01 + after)]
    tape = tmp_path / "damaged.tape"
    tape.write_bytes(tape_of(reads, random.Random(1)))
    lines = live(tape, pure, "-n")
    assert lines[2].endswith(SHOWN) and len(lines) == 5, lines
    records = [(data, T0 + round((at - 100.0) * 1000) * 10**6) for data, at in reads]
    assert decode(records, "pcap", pure, tmp_path)[2] == f"     3  0.500000000   {SHOWN}"


@ENGINES
def test_a_damaged_answer_at_a_silence(pure: bool, tmp_path: Path) -> None:
    """The answer awaited, its last byte damaged: a damaged answer live and in the file (a guard: the end of the
    input already counted for the answer awaited)."""
    reads = [(POLL, 100.0), (ANSWER[:-1] + b"\x00", 100.01), (POLL, 101.0), (ANSWER, 101.01)]
    tape = tmp_path / "answer.tape"
    tape.write_bytes(tape_of(reads, random.Random(1)))
    lines = live(tape, pure, "-n")
    assert "1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1" in lines[1] and "CRC BAD" in lines[1]
