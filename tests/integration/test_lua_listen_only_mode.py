"""The plugin follows Listen Only Mode per slave as vw3-decode does (tests/unit/test_listen_only_mode.py): after
08/04 (to the slave or broadcast) the slave's requests say it does not answer and are not unanswered, until
08/01, which says it ends the mode. Before, each request was unanswered ("No response"). Real tshark with
-X lua_script:lua/vw3.lua, -2 and one pass."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
LISTEN_ONLY, RESTART = rtu("0C 08 0004 0000"), rtu("0C 08 0001 0000")
READ, ANSWER = rtu("0C 03 20D1 0001"), rtu("0C 03 02 0003")
BROADCAST_LISTEN_ONLY, BROADCAST_RESTART, OTHER = rtu("00 08 0004 0000"), rtu("00 08 0001 0000"), rtu("05 03 20D1 0001")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.slave", "-e", "vw3.kind", "-e", "vw3.unanswered",
          "-e", "vw3.note"]
NOTE = "no response expected: the spec's server returns none"


def tshark(frames: list[tuple[bytes, float]], tmp_path: Path, two_pass: bool) -> list[str]:
    pcap = write_pcap(tmp_path / "lo.pcap", [(frame, T0 + at) for frame, at in frames])
    result = run_tshark(pcap, *FIELDS, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_slave_in_listen_only_mode(tmp_path: Path, two_pass: bool) -> None:
    # (the slave answers only the master's repeat of the 08/01 that ended the mode)
    frames = [(LISTEN_ONLY, 0.0), (READ, 1.0), (READ, 2.0), (RESTART, 3.0), (RESTART, 3.5), (RESTART, 3.52),
              (READ, 4.0), (ANSWER, 4.02)]
    assert tshark(frames, tmp_path, two_pass) == [
        f"12;1;;{NOTE}",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this",
        "12;1;;",
        "12;2;;",
        "12;1;;",
        "12;2;;",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_same_08_01_again_is_no_answer(tmp_path: Path, two_pass: bool) -> None:
    # (before: the second 08/01, 20 ms after the first, was taken for the echo the spec's server never sends)
    frames = [(LISTEN_ONLY, 0.0), (RESTART, 3.0), (RESTART, 3.02), (READ, 4.0), (ANSWER, 4.02)]
    assert tshark(frames, tmp_path, two_pass)[2:] == [
        "12;1;1;" if two_pass else "12;1;;",  # (one pass: its wait has not ended yet)
        "12;1;;",
        "12;2;;",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_broadcast_08_04(tmp_path: Path, two_pass: bool) -> None:
    frames = [(BROADCAST_LISTEN_ONLY, 0.0), (READ, 0.1), (OTHER, 0.2), (RESTART, 0.3), (READ, 0.4), (ANSWER, 0.42),
              (OTHER, 0.5), (BROADCAST_RESTART, 0.6), (OTHER, 0.7), (OTHER, 2.0)]
    assert tshark(frames, tmp_path, two_pass) == [
        "0;1;;",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04, broadcast): it does not answer",
        "5;1;;slave 5 is in listen-only mode since #1 (08/04, broadcast): it does not answer",
        "12;1;;slave 12 leaves listen-only mode (since #1, 08/04, broadcast): the spec's server does not answer this",
        "12;1;;",
        "12;2;;",
        "5;1;;slave 5 is in listen-only mode since #1 (08/04, broadcast): it does not answer",
        "0;1;;",
        "5;1;1;" if two_pass else "5;1;;",
        "5;1;;the capture ends before any response: not known whether it was answered" if two_pass else "5;1;;",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_damaged_08_01_does_not_end_it(tmp_path: Path, two_pass: bool) -> None:
    # (as vw3-decode: tests/unit/test_listen_only_mode.py; a random ASCII session found them apart)
    damaged = RESTART[:-1] + bytes([RESTART[-1] ^ 0xFF])
    frames = [(LISTEN_ONLY, 0.0), (damaged, 1.0), (READ, 2.0), (RESTART, 3.0), (READ, 4.0), (ANSWER, 4.02)]
    assert tshark(frames, tmp_path, two_pass)[1:] == [
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this",
        "12;1;;",
        "12;2;;",
    ]


def ascii_line(frame: bytes) -> bytes:
    """The RTU frame's ADU as a Modbus ASCII line (':' hex LRC CR LF)."""
    adu = frame[:-2]
    return b":" + (adu + bytes([-sum(adu) & 0xFF])).hex().upper().encode() + b"\r\n"


@pytest.mark.parametrize("two_pass", [True, False])
def test_in_ascii_as_in_rtu(tmp_path: Path, two_pass: bool) -> None:
    # (as tests/unit/test_listen_only_mode.py test_in_ascii_as_in_rtu: 08/01 ends the mode unanswered, the same
    # again is the master's repeat, which the slave answers; a line whose LRC fails ends nothing)
    damaged = ascii_line(RESTART).replace(b"EB\r\n", b"EC\r\n")  # (LRC EB)
    restart = ascii_line(RESTART)  # (the master's lines in lower-case hex, the slave's in upper case)
    lines = [ascii_line(LISTEN_ONLY), damaged, ascii_line(READ), restart.lower(), restart.lower(), restart,
             ascii_line(READ), ascii_line(ANSWER)]
    pcap = write_pcap(tmp_path / "lo-ascii.pcap", [(line, T0 + 0.5 * k) for k, line in enumerate(lines)])
    result = run_tshark(pcap, *FIELDS, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == [
        f"12;1;;{NOTE}",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 is in listen-only mode since #1 (08/04): it does not answer",
        "12;1;;slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this",
        "12;1;;",
        "12;2;;",
        "12;1;;",
        "12;2;;",
    ]


def test_a_slave_that_answers_is_not_in_the_mode(tmp_path: Path) -> None:
    # (pairing.py _heard: the request's note is taken back, the answer says why it pairs; -2 shows it final)
    frames = [(LISTEN_ONLY, 0.0), (READ, 1.0), (ANSWER, 1.02), (READ, 2.0), (READ, 3.5)]
    assert tshark(frames, tmp_path, True) == [
        f"12;1;;{NOTE}",
        "12;1;;",
        "12;2;;slave 12 answers: it is not in listen-only mode (#1, 08/04)",
        "12;1;1;",
        "12;1;;the capture ends before any response: not known whether it was answered",
    ]
