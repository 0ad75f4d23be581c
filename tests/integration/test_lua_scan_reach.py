"""The plugin's CRC scan does not reach across a record that is a frame of its own (lua/src/rtu.lua framed_reach,
framing/reach.py _framed_reach), in tshark's single pass and with -2: a record whose first bytes read as a code
without a length rule (slave 41's user-defined function 70; an FC8/00 Return Query Data), then a request right
after it whose CRC over both records checks by chance, was read as one frame ('41 User-defined function 70
request', the request lost). Exact Info, and every field as vw3-decode says it (reading once; reading twice)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])  # (what one pass cannot know when it shows a request)

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
READ, ANSWERED = "12 Read Holding Registers request 8400..8402 (3)", "12 Read Holding Registers response 8400..8402 (3)"
# (the last two bytes of each chosen so that it and the request after it check as one frame)
USER = bytes.fromhex("2946a54dca182530bb1d6d132cded6237b2ed91e3f72480b")
FC8 = bytes.fromhex("0c0800001234bb74")
QUERY = "12 Diagnostics request 00h Return Query Data data 1234bb740c0320d00003"
CHARACTER = 11 / 19200


def _infos(pcap: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def _same_as_vw3_decode(pcap: Path, ignore: frozenset[str] = frozenset()) -> None:
    # (one pass shows record 3's noise, settled by record 4, in record 4 too: as vw3-decode reading once)
    one, _, _ = lua_items(pcap, two_pass=False)
    differences = compare(python_items(pcap, one_pass=True), one, ignore=LATER | ignore)
    assert not differences, "\n".join(differences[:40])
    two, _, _ = lua_items(pcap)
    differences = compare(python_items(pcap), two)
    assert not differences, "\n".join(differences[:40])


def _capture(tmp_path: Path, first: bytes, then: tuple[bytes, float]) -> Path:
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (first, 2.0), (REQUEST, 2.0 + len(first) * CHARACTER), then,
               (REQUEST, 4.0), (ANSWER, 4.01)]
    return write_pcap(tmp_path / "scan.pcap", [(data, 1700000000 + time) for data, time in records])


def test_a_user_defined_scan_stops_at_a_record_that_is_a_frame(tmp_path: Path) -> None:
    pcap = _capture(tmp_path, USER, (ANSWER, 2.03))
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", "(24 bytes continue)",
        f"noise (24 bytes) from #3; {READ} [provisional]", ANSWERED, READ, ANSWERED]
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, "noise (24 bytes)", READ, ANSWERED, READ, ANSWERED]
    _same_as_vw3_decode(pcap)


def test_an_fc8_scan_stops_at_a_record_that_is_a_frame(tmp_path: Path) -> None:
    # (then the 16 bytes in one record: a Return Query Data request of its own, not the echo of one)
    pcap = _capture(tmp_path, FC8, (FC8 + REQUEST, 2.03))
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", "(8 bytes continue)",
        f"noise (8 bytes) from #3; {READ} [provisional]", f"{QUERY} [provisional]", f"{READ} [provisional]", ANSWERED]
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, "noise (8 bytes)", READ, QUERY, READ, ANSWERED]
    _same_as_vw3_decode(pcap)


def test_a_scan_after_a_request_gives_up_at_a_record_that_is_a_frame(tmp_path: Path) -> None:
    # ('29 46' after a request in its record waited for up to 256 bytes: every later record '(N bytes continue)')
    first = rtu("0C 03 20D1 0001") + bytes.fromhex("29460102")
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (first, 2.0), (REQUEST, 3.0), (ANSWER, 3.01), (REQUEST, 4.0),
               (ANSWER, 4.01)]
    pcap = write_pcap(tmp_path / "held.pcap", [(data, 1700000000 + time) for data, time in records])
    other = "12 Read Holding Registers request 8401"
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", f"{other} [provisional]; (4 bytes continue)",
        f"noise (4 bytes) from #3; {READ} [provisional]", ANSWERED, READ, ANSWERED]
    assert _infos(pcap, two_pass=True) == [
        READ, ANSWERED, f"{other}; noise (4 bytes)", READ, ANSWERED, READ, ANSWERED]
    _same_as_vw3_decode(pcap)


def test_a_damaged_request_before_a_scan_start_is_settled_by_the_next_record(tmp_path: Path) -> None:
    # (whether the damaged request ends where a frame starts: the scan from '29 46' waited for up to 256 bytes)
    first = REQUEST[:-1] + bytes([REQUEST[-1] ^ 1]) + bytes.fromhex("29460102")
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (first, 2.0), (REQUEST, 3.0), (ANSWER, 3.01), (REQUEST, 4.0),
               (ANSWER, 4.01)]
    pcap = write_pcap(tmp_path / "damaged.pcap", [(data, 1700000000 + time) for data, time in records])
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", "(12 bytes continue)",
        f"noise (12 bytes) from #3; {READ} [provisional]", ANSWERED, READ, ANSWERED]
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, "noise (12 bytes)", READ, ANSWERED, READ, ANSWERED]
    _same_as_vw3_decode(pcap)
