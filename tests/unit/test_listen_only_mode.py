"""Listen Only Mode followed per slave (Modbus Application Protocol 6.8.1): after 08/04 Force Listen Only Mode
(to the slave, or broadcast to every slave) the slave answers nothing until 08/01 Restart Communications
Option, which it does not answer either. Its requests meanwhile say why no answer comes and are not counted
"no reply" nor poll misses. Before, each printed a bare "[no response]" and counted as no reply (a wiring
hunt for a slave that was told to keep quiet). An exception to the 08/04 (a server without it) leaves the
slave out of the mode. Exact output for exact bytes (the hunter's lo.pcap), the engine and
VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import io
import re
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, use_engine

T0 = 1700000000.0
LISTEN_ONLY, RESTART = rtu("0C 08 0004 0000"), rtu("0C 08 0001 0000")
READ, ANSWER = rtu("0C 03 20D1 0001"), rtu("0C 03 02 0003")
BROADCAST_LISTEN_ONLY, BROADCAST_RESTART = rtu("00 08 0004 0000"), rtu("00 08 0001 0000")
REFUSED = rtu("0C 88 01")


def decode(frames: list[tuple[bytes, float]], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, *options: str) -> str:
    path = tmp_path / "lo.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for frame, at in frames:
            writer.write(frame, T0 + at)
    outputs = []
    for pure in (False, True):
        use_engine(monkeypatch, pure)
        out, err = io.StringIO(), io.StringIO()
        assert run([str(path), "-n", *options], Environment(io.BytesIO(b""), out, err, False, False)) == 0
        assert err.getvalue() == ""
        outputs.append(out.getvalue())
    assert outputs[0] == outputs[1]
    return outputs[0]


def lines(text: str) -> list[str]:
    return [re.sub(r"\s+", " ", line.strip()) for line in text.splitlines()]


# (the 08/01 that ends the mode is not answered: the master repeats it, and the slave answers the repeat)
HUNT = [(LISTEN_ONLY, 0.0), (READ, 1.0), (READ, 2.0), (RESTART, 3.0), (RESTART, 3.5), (RESTART, 3.52), (READ, 4.0),
        (ANSWER, 4.02)]


def test_the_requests_of_a_slave_in_listen_only_mode_say_why_none_is_answered(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert lines(decode(HUNT, tmp_path, monkeypatch)) == [
        "1 0.000000 12 request Diagnostics 04h Force Listen Only Mode = 0 "
        "[no response expected: the spec's server returns none] CRC ok",
        "2 1.000000 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] CRC ok",
        "3 2.000000 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] CRC ok",
        "4 3.000000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this] CRC ok",
        "5 3.500000 12 request Diagnostics 01h Restart Communications Option = 0 CRC ok",
        "6 3.520000 12 response Diagnostics 01h Restart Communications Option = 0 [#5, 20.0 ms] CRC ok",
        "7 4.000000 12 request Read Holding Registers 8401 CRC ok",
        "8 4.020000 12 response Read Holding Registers 8401: 8401=3 [#7, 20.0 ms] CRC ok",
    ]


def test_the_same_08_01_again_is_no_answer(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The spec's server in the mode does not answer the 08/01 that ends it: the same frame 20 ms later is the
    # master's repeat, a request (it awaits an answer: [no response]), not the echo (before: '[#2, 20.0 ms]').
    frames = [(LISTEN_ONLY, 0.0), (RESTART, 3.0), (RESTART, 3.02), (READ, 4.0), (ANSWER, 4.02)]
    assert lines(decode(frames, tmp_path, monkeypatch))[2:] == [
        "3 3.020000 12 request Diagnostics 01h Restart Communications Option = 0 [no response] CRC ok",
        "4 4.000000 12 request Read Holding Registers 8401 CRC ok",
        "5 4.020000 12 response Read Holding Registers 8401: 8401=3 [#4, 20.0 ms] CRC ok",
    ]


def test_stats_count_them_not_as_no_reply(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    table = lines(decode(HUNT, tmp_path, monkeypatch, "--stats"))
    assert "12 3 Read Holding Registers 3 1 0 0" in table
    assert "12 8 Diagnostics 3 1 0 0" in table  # (08/04, 08/01 and its repeat, which is answered)
    # (one miss: the cycle the master skipped for the 08/01; none for the requests it did not answer)
    assert "12 3 Read Holding Registers 8401 3 1000.0 0.0 1" in table


def test_after_a_broadcast_08_04_every_slave_is_in_it_until_its_own_08_01(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    other = rtu("05 03 20D1 0001")
    frames = [(BROADCAST_LISTEN_ONLY, 0.0), (READ, 0.1), (other, 0.2), (RESTART, 0.3), (READ, 0.4), (ANSWER, 0.42),
              (other, 0.5), (BROADCAST_RESTART, 0.6), (other, 0.7)]
    assert lines(decode(frames, tmp_path, monkeypatch)) == [
        "1 0.000000 0 request Diagnostics 04h Force Listen Only Mode = 0 [broadcast] CRC ok",
        "2 0.100000 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04, broadcast): it does not answer] CRC ok",
        "3 0.200000 5 request Read Holding Registers 8401 "
        "[slave 5 is in listen-only mode since #1 (08/04, broadcast): it does not answer] CRC ok",
        "4 0.300000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 leaves listen-only mode (since #1, 08/04, broadcast): the spec's server does not answer this] CRC ok",
        "5 0.400000 12 request Read Holding Registers 8401 CRC ok",
        "6 0.420000 12 response Read Holding Registers 8401: 8401=3 [#5, 20.0 ms] CRC ok",
        "7 0.500000 5 request Read Holding Registers 8401 "
        "[slave 5 is in listen-only mode since #1 (08/04, broadcast): it does not answer] CRC ok",
        "8 0.600000 0 request Diagnostics 01h Restart Communications Option = 0 [broadcast] CRC ok",
        "9 0.700000 5 request Read Holding Registers 8401 "
        "[the capture ends before any response: not known whether it was answered] CRC ok",
    ]


def test_an_exception_to_08_04_leaves_the_slave_out_of_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    frames = [(LISTEN_ONLY, 0.0), (REFUSED, 0.02), (READ, 1.0), (READ, 2.0)]
    assert lines(decode(frames, tmp_path, monkeypatch))[2:4] == [
        "3 1.000000 12 request Read Holding Registers 8401 [no response] CRC ok",
        "4 2.000000 12 request Read Holding Registers 8401 "
        "[the capture ends before any response: not known whether it was answered] CRC ok",
    ]


def test_a_damaged_08_01_does_not_end_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (a slave acts on no frame whose check fails: it stays in the mode, and the 08/01 says so; before, the
    # note said it left while the next request still found it in the mode, and the plugin said otherwise)
    damaged = RESTART[:-1] + bytes([RESTART[-1] ^ 0xFF])
    frames = [(LISTEN_ONLY, 0.0), (damaged, 1.0), (READ, 2.0), (RESTART, 3.0), (READ, 4.0), (ANSWER, 4.02)]
    assert lines(decode(frames, tmp_path, monkeypatch))[1:] == [
        "2 1.000000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] "
        "CRC BAD (received 0x29B0, expected 0xD6B0)",
        "3 2.000000 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] CRC ok",
        "4 3.000000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this] CRC ok",
        "5 4.000000 12 request Read Holding Registers 8401 CRC ok",
        "6 4.020000 12 response Read Holding Registers 8401: 8401=3 [#5, 20.0 ms] CRC ok",
    ]


def ascii_line(frame: bytes) -> bytes:
    """The RTU frame's ADU as a Modbus ASCII line (':' hex LRC CR LF)."""
    adu = frame[:-2]
    return b":" + (adu + bytes([-sum(adu) & 0xFF])).hex().upper().encode() + b"\r\n"


LOWER_CASE = "lower-case hex digits (the spec wants upper case)"


def test_in_ascii_as_in_rtu(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (and the plugin alike: tests/integration/test_lua_listen_only_mode.py test_in_ascii_as_in_rtu)
    damaged = ascii_line(RESTART).replace(b"EB\r\n", b"EC\r\n")  # (LRC EB)
    # (the master's lines in lower-case hex, the slave's in upper case: the repeat is the same request)
    restart = ascii_line(RESTART)
    sent = [ascii_line(LISTEN_ONLY), damaged, ascii_line(READ), restart.lower(), restart.lower(), restart,
            ascii_line(READ), ascii_line(ANSWER)]
    frames = [(line, 0.5 * k) for k, line in enumerate(sent)]
    assert lines(decode(frames, tmp_path, monkeypatch, "--mode", "ascii"))[1:] == [
        "2 0.500000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] "
        "LRC BAD (received 0xEC, expected 0xEB)",
        "3 1.000000 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] LRC ok",
        "4 1.500000 12 request Diagnostics 01h Restart Communications Option = 0 "
        "[slave 12 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this] "
        f"[warning: {LOWER_CASE}] LRC ok",
        f"5 2.000000 12 request Diagnostics 01h Restart Communications Option = 0 [warning: {LOWER_CASE}] LRC ok",
        "6 2.500000 12 response Diagnostics 01h Restart Communications Option = 0 [#5, 500.0 ms] LRC ok",
        "7 3.000000 12 request Read Holding Registers 8401 LRC ok",
        "8 3.500000 12 response Read Holding Registers 8401: 8401=3 [#7, 500.0 ms] LRC ok",
    ]



# A slave taken to be in the mode that answers (not the request again, which is the master's repeat) did not take
# the 08/04 or restarted: its request keeps no "does not answer" note, the answer says why it pairs, and the
# slave is out of the mode (its next request unanswered is [no response]).
def test_a_slave_that_answers_is_not_in_the_mode(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    heard = [(LISTEN_ONLY, 0.0), (READ, 1.0), (ANSWER, 1.02), (READ, 2.0), (READ, 3.5)]
    assert lines(decode(heard, tmp_path, monkeypatch)) == [
        "1 0.000000 12 request Diagnostics 04h Force Listen Only Mode = 0 "
        "[no response expected: the spec's server returns none] CRC ok",
        "2 1.000000 12 request Read Holding Registers 8401 CRC ok",
        "3 1.020000 12 response Read Holding Registers 8401: 8401=3 [#2, 20.0 ms] "
        "[slave 12 answers: it is not in listen-only mode (#1, 08/04)] CRC ok",
        "4 2.000000 12 request Read Holding Registers 8401 [no response] CRC ok",
        "5 3.500000 12 request Read Holding Registers 8401 [the capture ends before any response: not known whether "
        "it was answered] CRC ok",
    ]
