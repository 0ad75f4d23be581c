"""tshark's single pass (no -2: how Wireshark dissects a live capture) shows each record's frame in that record
when its frame checks out and ends with it, whatever longer reading crossing its end might once have been:
after a broadcast request (its 00 read as a glitch byte before a 'slave 6, FC12' answer of 134 bytes) and an
exception from slave 0 ('slave 144, FC2' of 166 bytes), every later record showed '(N bytes continue)' and no
frame; an FC8/00 Return Query Data (a CRC scan, which waited for what follows it) showed nothing in its
record. Exact Info per record, one pass and -2, and every field as vw3-decode reading once says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
# (what one pass cannot know when it shows a request: the answer after it, test_lua_parity_auto.py)
LATER = frozenset(["response_frame", "unanswered"])

REQUEST, ANSWER = "0C 03 20D0 0003", "0C 03 06 8000 0003 0002"
ODD = {
    "broadcast": rtu("00 06 0C81 0001"),
    "exception_0": rtu("00 90 02"),
    "fc8_00": rtu("0C 08 0000 1234"),
}
READ, ANSWERED = "12 Read Holding Registers request 8400..8402 (3)", "12 Read Holding Registers response 8400..8402 (3)"
# (slave 0 read once while slave 12 may still get a device, which would name a broadcast: provisional)
SAID = {
    "broadcast": "0 Write Single Register request 3201 = 1 [provisional]",
    "exception_0": "0 Write Multiple Registers exception 2 (Illegal Data Address) [provisional]",
    "fc8_00": "12 Diagnostics request 00h Return Query Data = 4660 [provisional]",
}


def _pcap(tmp_path: Path, odd: str) -> Path:
    # /tmp/recall/bc.txt's shape: p.38's read and answer, the odd record 2 s later, then reads and answers
    records = [(rtu(REQUEST), 0.0), (rtu(ANSWER), 0.01), (ODD[odd], 2.01), (rtu(REQUEST), 2.06),
               (rtu(ANSWER), 2.07), (rtu(REQUEST), 4.07), (rtu(ANSWER), 4.12)]
    return write_pcap(tmp_path / f"{odd}.pcap", [(data, 1700000000 + time) for data, time in records])


def _infos(pcap: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


@pytest.mark.parametrize("odd", sorted(ODD))
def test_one_pass_shows_every_record_s_frame(tmp_path: Path, odd: str) -> None:
    pcap = _pcap(tmp_path, odd)
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", SAID[odd],
        f"{READ} [provisional]", ANSWERED, READ, ANSWERED]
    # (-2: the slave's choice over the whole capture, as vw3-decode FILE; the same frames)
    # (the broadcast's register named by the device chosen for the bus, as vw3-decode FILE names it)
    said = SAID[odd].replace(" [provisional]", "").replace("3201 = 1", "3201 ETA=Ready to switch on")
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, said, READ, ANSWERED, READ, ANSWERED]


@pytest.mark.parametrize("odd", sorted(ODD))
def test_one_pass_is_vw3_decode_reading_once(tmp_path: Path, odd: str) -> None:
    pcap = _pcap(tmp_path, odd)
    one, _, _ = lua_items(pcap, two_pass=False)
    stream = python_items(pcap, one_pass=True)
    assert len(stream) == 7
    differences = compare(stream, one, ignore=LATER)
    assert not differences, "\n".join(differences[:40])
    two, _, _ = lua_items(pcap)
    differences = compare(python_items(pcap), two)
    assert not differences, "\n".join(differences[:40])
