"""pymodbus's server (3.16) answers an FC8 04 (Force Listen Only Mode) with its sub-function alone, `01 08 00 04
81 D9` (ForceListenOnlyModeResponse: no data word), though the spec's slave returns no response (Application
Protocol 6.8.1). That frame, intact and too short for a request, is the 08/04's answer, warned, in vw3-decode
(decode/pairing.py _echoes_listen_only; engine and Python stages alike) and the plugin (lua/src/pairing.lua); the
slave is taken to be in the mode all the same, and its next answer says it is not (pymodbus keeps answering).
A master's repeat of the 08/04 holds the data word, 8 bytes: still a request, timed or not, within the timeout
or not (test_fc8_pairing: a master that sends 08/04 every 100 ms). Before, the answer was read as a second,
malformed request (`[slave 1 is in listen-only mode since #1 ...] [warning: diagnostic data (none) is not what
sub-function 04h takes (0000): a server answers exception 03]`), a request no master sent."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

LISTEN, ANSWERED, READ, VALUE = "01 08 0004 0000", "01 08 0004", "01 03 0000 0001", "01 03 02 0007"
WARNING = "an answer to 08/04 (Force Listen Only Mode), which the spec's slave does not answer"
LENGTH = "frame length 6 disagrees with the spec's layout (8 bytes), its CRC good"
ANSWERED_LINES = [
    "     1     0.000000   1 request   Diagnostics 04h Force Listen Only Mode = 0"
    " [no response expected: the spec's server returns none]  CRC ok",
    "     2     0.012000   1 response  Diagnostics 04h Force Listen Only Mode [#1, 12.0 ms]"
    f" [warning: {LENGTH}] [warning: {WARNING}]  CRC ok",
    "     3     0.500000   1 request   Read Holding Registers 0  CRC ok",
    "     4     0.510000   1 response  Read Holding Registers 0: 0=7 [#3, 10.0 ms]"
    " [slave 1 answers: it is not in listen-only mode (#1, 08/04)]  CRC ok",
]
REPEATED_LINES = [
    "     1     0.000000   1 request   Diagnostics 04h Force Listen Only Mode = 0"
    " [no response expected: the spec's server returns none]  CRC ok",
    "     2     0.012000   1 request   Diagnostics 04h Force Listen Only Mode = 0"
    " [slave 1 is in listen-only mode since #1 (08/04): it does not answer]  CRC ok",
]


def _pcap(tmp_path: Path, name: str, frames: list[tuple[str, float]]) -> Path:
    return write_pcap(tmp_path / name, [(rtu(frame), 1700000000 + at) for frame, at in frames])


@pytest.fixture
def answered(tmp_path: Path) -> Path:
    return _pcap(tmp_path, "answered.pcap", [(LISTEN, 0), (ANSWERED, 0.012), (READ, 0.5), (VALUE, 0.51)])


@pytest.fixture
def repeated(tmp_path: Path) -> Path:
    return _pcap(tmp_path, "repeated.pcap", [(LISTEN, 0), (LISTEN, 0.012)])


@pytest.mark.parametrize("pure", [False, True])
def test_the_sub_function_alone_answers_the_08_04(answered: Path, repeated: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(answered)])
    assert (status, err) == (0, "")
    assert out.splitlines() == ANSWERED_LINES
    status, out, err = run_cli([str(repeated)])
    assert (status, err) == (0, "")
    assert out.splitlines() == REPEATED_LINES


def test_untimed_alike(tmp_path: Path) -> None:
    raw = tmp_path / "untimed.bin"
    raw.write_bytes(rtu(LISTEN) + rtu(ANSWERED) + rtu(LISTEN) + rtu(LISTEN))
    status, out, err = run_cli([str(raw), "-T", "fields", "-e", "kind", "-e", "request_frame"])
    assert (status, err) == (0, "")
    assert out.splitlines() == ["request\t", "response\t1", "request\t", "request\t"]


def test_the_plugin_reads_the_answer_alike(answered: Path, repeated: Path) -> None:
    got = run_tshark(answered, "-T", "fields", "-E", "separator=|", "-e", "vw3.kind", "-e", "vw3.request_frame",
                     "-e", "vw3.warning")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == ["1||", f"2|1|{LENGTH},{WARNING}", "1||", "2|3|"]
    got = run_tshark(repeated, "-T", "fields", "-e", "vw3.kind")
    assert got.stdout.split() == ["1", "1"]
    # One pass: the short frame is framed once the next packet's bytes come (`from #2`), an answer there too.
    got = run_tshark(answered, "-T", "fields", "-e", "_ws.col.Info", two_pass=False)
    assert got.stdout.splitlines()[2].startswith("1 Diagnostics response 04h Force Listen Only Mode [provisional] from #2;")
