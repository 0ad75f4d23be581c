"""tshark's single pass (no -2) where a reading waits for bytes past a record that is a frame of its own
(framing/reach.py _crosses_framed_record, lua/src/rtu.lua crosses_framed_record): 'ff ff 01 b0' before a request
in one record read 'ff 01' as slave 255 FC1 whose answer would be 181 bytes, and the request cut short by the
next record ('01 03 00 00 00', a repeated request's first bytes) as a request of 8 bytes: that record and every
later one showed '(N bytes continue)' to the end of the capture. (Noise and frames a later record settles: shown in
that record too in one pass, test_lua_one_pass_noise.py.) A reading that would swallow a record that is a
frame is none. Exact Info, one pass and -2, and every field as vw3-decode says it (reading once; reading twice)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])  # (what one pass cannot know when it shows a request)

REQUEST, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 8000 0003 0002")
READ, ANSWERED = "12 Read Holding Registers request 8400..8402 (3)", "12 Read Holding Registers response 8400..8402 (3)"
ONE, ONE_ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")
READ_ONE, ONE_ANSWERED = "1 Read Holding Registers request 0", "1 Read Holding Registers response 0"


def _infos(pcap: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def test_noise_read_as_a_long_answer_before_records_that_are_frames(tmp_path: Path) -> None:
    records = [(REQUEST, 0.0), (ANSWER, 0.01), (bytes.fromhex("ffff01b0") + REQUEST, 2.0), (ANSWER, 2.06),
               (REQUEST, 4.0), (ANSWER, 4.01)]
    pcap = write_pcap(tmp_path / "long.pcap", [(data, 1700000000 + time) for data, time in records])
    # (record 3's noise and request, settled by record 4: shown in record 4 in one pass, in record 3 by -2;
    # 'ff' is noise at once, the rest waits)
    assert _infos(pcap, two_pass=False) == [
        f"{READ} [provisional]", f"{ANSWERED} [provisional]", "noise (1 byte so far); (11 bytes continue)",
        f"noise (4 bytes) from #3; {READ} [provisional] from #3; {ANSWERED}", READ, ANSWERED]
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, f"noise (4 bytes); {READ}", ANSWERED, READ, ANSWERED]
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)


def test_a_request_cut_short_by_the_next_record(tmp_path: Path) -> None:
    records = [(ONE, 0.0), (ONE[:5], 1.0), (ONE, 2.0), (ONE_ANSWER, 2.01)]
    pcap = write_pcap(tmp_path / "cut.pcap", [(data, 1700000000 + time) for data, time in records])
    # (record 2's noise, settled by record 3: shown in record 3 in one pass, in record 2 by -2)
    assert _infos(pcap, two_pass=False) == [
        f"{READ_ONE} [provisional]", "(5 bytes continue)", f"noise (5 bytes) from #2; {READ_ONE} [provisional]",
        f"{ONE_ANSWERED} [provisional]"]
    assert _infos(pcap, two_pass=True) == [READ_ONE, "noise (5 bytes)", READ_ONE, ONE_ANSWERED]
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)
