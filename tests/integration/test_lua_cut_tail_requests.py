"""The plugin as vw3-decode on a request cut by the end of the capture after a request awaiting its answer
(tests/differential/test_cut_tail_requests.py; lua/src/stream.lua not_the_answer): '0C 03 20 D0' after a read
of 3 registers of slave 12 was 'the capture ends inside the response (4 of 37 bytes)' (0x20 read as a byte
count), on the request and as the noise's reason, ':0C0320D0' '(9 of 75 bytes)'. The request implies an answer
of 11 bytes: the bytes are the request reading. An answer cut stays one. Exact fields (tshark -2) and every
field as vw3-decode says it; one pass shows the tail as bytes that continue (the end of the capture comes
after tshark shows it)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
POLL, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 0001 0002 0003")
ASCII_POLL = b":0C0320D00003FE\r\n"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.note", "-e", "vw3.noise.reason"]
UNKNOWN = ("the capture ends {} ms after the request, within the 1000 ms timeout: not known whether it was"
           " answered")
CUT_POLL = "4;;the capture ends inside a request ({} of {} bytes)"


def _fields(pcap: Path, two_pass: bool = True) -> list[str]:
    got = run_tshark(pcap, *FIELDS, two_pass=two_pass)
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def _same_as_vw3_decode(pcap: Path) -> None:
    differences = compare(python_items(pcap), lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])


def test_the_next_poll_cut_after_an_unanswered_one(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "cut.pcap", [(POLL, T0), (POLL[:4], T0 + 1.0)])
    assert _fields(pcap) == [f"1;{UNKNOWN.format('1000.0')};", CUT_POLL.format(4, 8)]
    assert _fields(pcap, two_pass=False) == ["1;;", ";;"]
    _same_as_vw3_decode(pcap)


def test_an_answer_cut_stays_one(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "answer.pcap", [(POLL, T0), (ANSWER[:5], T0 + 0.01)])
    cut = "the capture ends inside the response (5 of 11 bytes)"
    assert _fields(pcap) == [f"1;{cut};", f"4;;{cut}"]
    _same_as_vw3_decode(pcap)


def test_the_next_poll_after_an_answer(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "answered.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (POLL[:4], T0 + 1.0)])
    assert _fields(pcap) == ["1;;", "2;;", CUT_POLL.format(4, 8)]  # (lua/src/rtu.lua cut_request)
    _same_as_vw3_decode(pcap)


def test_ascii(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "cut-ascii.pcap", [(ASCII_POLL, T0), (b":0C0320D0", T0 + 0.01)])
    assert _fields(pcap) == [f"1;{UNKNOWN.format('10.0')};", CUT_POLL.format(9, 17)]
    _same_as_vw3_decode(pcap)
