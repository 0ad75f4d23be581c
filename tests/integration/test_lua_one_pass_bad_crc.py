"""tshark's single pass (no -2: how Wireshark dissects a live capture) after an answer with a bad CRC: the
framer waited for bytes past the answer's record (a frame starting inside it, '00 03 00 02 ...', could have
crossed that record's end), so that record and every later one showed '(N bytes continue)' and no frame, up
to the end of the capture. Records that are frames say no frame crosses their ends (framing/rtu.py _match,
lua/src/rtu.lua match): an answer that is its own record is shown in it; one that shares its record with the request
is settled by the next record, a frame (one pass shows it in that record, from its own bytes; -2 in its own). Exact Info, one pass and
-2, and every field as vw3-decode says it (reading once; reading twice)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes, lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])  # (what one pass cannot know when it shows a request)

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
BAD = ANSWER[:-1] + bytes([ANSWER[-1] ^ 1])  # (CRC E5 17 for E4 17)
READ, ANSWERED = "12 Read Holding Registers request 8400..8402 (3)", "12 Read Holding Registers response 8400..8402 (3)"
LATE = [(REQUEST, 2.0), (ANSWER, 2.01), (REQUEST, 4.0), (ANSWER, 4.05)]


def _pcap(tmp_path: Path, name: str, records: list[tuple[bytes, float]]) -> Path:
    return write_pcap(tmp_path / f"{name}.pcap", [(data, 1700000000 + time) for data, time in records])


def _infos(pcap: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def test_an_answer_with_a_bad_crc_in_its_own_record(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path, "own", [(REQUEST, 0.0), (BAD, 0.01), *LATE])
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional] BAD CRC", f"{READ} [provisional]",
        f"{ANSWERED} [provisional]", f"{READ} [provisional]", ANSWERED]
    assert _infos(pcap, two_pass=True) == [READ, f"{ANSWERED} BAD CRC", READ, ANSWERED, READ, ANSWERED]
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)


def test_an_answer_with_a_bad_crc_after_its_request_in_one_record(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path, "together", [(REQUEST + BAD, 0.0), *LATE])
    # (the answer, settled by record 2: shown in record 2 in one pass, in record 1 by -2)
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]; (11 bytes continue)", f"{ANSWERED} [provisional] BAD CRC from #1; {READ} [provisional]",
        f"{ANSWERED} [provisional]", f"{READ} [provisional]", ANSWERED]
    assert _infos(pcap, two_pass=True) == [f"{READ}; {ANSWERED} BAD CRC", READ, ANSWERED, READ, ANSWERED]
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)
