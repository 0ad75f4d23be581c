"""A master's retry of a request its answer echoes (FC5, FC6, FC8's Return Query Data: the answer is the
request's bytes), later than --timeout: a request, and the next identical frame its answer (hunter1's
retry.pcap: before, the retry was 'response [no request] [warning: ... later than the 400 ms timeout]' and
the drive's echo 'request [no response]'). Exact lines, the engine and the Python stages
(VW3_PURE_PYTHON=1) alike (assert_same); RTU and ASCII; --stats; a live capture's expiry (Pairer.expire).
The framer, which has no timeout, read the retry as an answer: the frames after it take the kind it would
have given them had it known (the master's next write is a request, not an answer to nothing)."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.decode.pairing import Pairer
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame, Kind
from helpers import rtu
from test_timed_summary import assert_same, write_pcap

T0 = 1_700_000_000 * 10**9
HSP = rtu("0C 06 0C20 01F4")  # write HSP (3104) = 500: 50.0 Hz
HSP_LOW = rtu("0C 06 0C20 01C2")  # 45.0 Hz
READ, READ_ANSWER = rtu("0C 03 0C81 0002"), rtu("0C 03 04 0001 0002")
CHCF = rtu("0C 10 20D1 0001 02 0003")
CHCF_WRITTEN = rtu("0C 10 20D1 0001")


def pcap(tmp_path: Path, frames: list[tuple[float, bytes]], name: str = "retry.pcap") -> str:
    path = tmp_path / name
    write_pcap(path, [(frame, T0 + round(seconds * 10**9)) for seconds, frame in frames])
    return str(path)


HUNTER = [(0.0, HSP), (0.5, HSP), (0.512, HSP), (0.6, READ), (0.612, READ_ANSWER),
          (1.0, CHCF), (1.3, CHCF), (1.312, CHCF_WRITTEN)]
HUNTER_LINES = (
    "     1  0.000000000  12 request   Write Single Register 3104 HSP=50.0 Hz [no response]  CRC ok\n"
    "     2  0.500000000  12 request   Write Single Register 3104 HSP=50.0 Hz  CRC ok\n"
    "     3  0.512000000  12 response  Write Single Register 3104 HSP=50.0 Hz [#2, 12.0 ms]  CRC ok\n"
    "     4  0.600000000  12 request   Read Holding Registers 3201..3202 (2)  CRC ok\n"
    "     5  0.612000000  12 response  Read Holding Registers 3201..3202 (2): ETA=Ready to switch on RFR=0.2 Hz"
    " [#4, 12.0 ms]  CRC ok\n"
    "     6  1.000000000  12 request   Write Multiple Registers 8401: CHCF=IO (I/O profile) [no response]  CRC ok\n"
    "     7  1.300000000  12 request   Write Multiple Registers 8401: CHCF=IO (I/O profile)  CRC ok\n"
    "     8  1.312000000  12 response  Write Multiple Registers 8401 written [#7, 12.0 ms]  CRC ok\n"
)


def test_a_retry_past_the_timeout_is_a_request_and_the_echo_after_it_its_answer(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = pcap(tmp_path, HUNTER)
    out, _ = assert_same([capture, "--profile", "atv71", "--timeout", "0.4"], monkeypatch)
    assert out == HUNTER_LINES
    # (was: #2 response [no request] [warning: response 500.0 ms after request #1, later than the 400 ms
    # timeout: not its answer], #3 request [no response])
    out, _ = assert_same([capture, "--profile", "atv71", "--timeout", "0.4", "--stats"], monkeypatch)
    assert "   12  6 Write Single Register        2     1                     1        0\n" in out
    assert "   12  6 Write Single Register          1  12.0    12.0  12.0  12.0\n" in out


def test_within_the_timeout_the_identical_frame_is_the_answer(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (the timeout, 1 s, is what tells a retry: 500 ms is an answer's time then; no look-ahead)
    out, _ = assert_same([pcap(tmp_path, HUNTER[:3]), "--profile", "atv71"], monkeypatch)
    assert out == (
        "     1  0.000000000  12 request   Write Single Register 3104 HSP=50.0 Hz  CRC ok\n"
        "     2  0.500000000  12 response  Write Single Register 3104 HSP=50.0 Hz [#1, 500.0 ms]  CRC ok\n"
        "     3  0.512000000  12 request   Write Single Register 3104 HSP=50.0 Hz "
        "[the capture ends before any response: not known whether it was answered]  CRC ok\n"
    )


def test_after_the_retry_answer_the_next_write_is_a_request(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The framer took the retry's answer for a request and awaits an answer from 12/FC6: the master's next
    # write (another value) is still a request, its echo its answer; then the same write retried twice.
    frames = [(0.0, HSP), (0.5, HSP), (0.512, HSP), (0.6, HSP_LOW), (0.612, HSP_LOW),
              (1.0, HSP), (1.5, HSP), (2.0, HSP), (2.01, HSP), (2.1, READ), (2.11, READ_ANSWER)]
    out, _ = assert_same([pcap(tmp_path, frames), "--profile", "atv71", "--timeout", "0.4"], monkeypatch)
    assert out == (
        "     1  0.000000000  12 request   Write Single Register 3104 HSP=50.0 Hz [no response]  CRC ok\n"
        "     2  0.500000000  12 request   Write Single Register 3104 HSP=50.0 Hz  CRC ok\n"
        "     3  0.512000000  12 response  Write Single Register 3104 HSP=50.0 Hz [#2, 12.0 ms]  CRC ok\n"
        "     4  0.600000000  12 request   Write Single Register 3104 HSP=45.0 Hz  CRC ok\n"
        "     5  0.612000000  12 response  Write Single Register 3104 HSP=45.0 Hz [#4, 12.0 ms]  CRC ok\n"
        "     6  1.000000000  12 request   Write Single Register 3104 HSP=50.0 Hz [no response]  CRC ok\n"
        "     7  1.500000000  12 request   Write Single Register 3104 HSP=50.0 Hz [no response]  CRC ok\n"
        "     8  2.000000000  12 request   Write Single Register 3104 HSP=50.0 Hz  CRC ok\n"
        "     9  2.010000000  12 response  Write Single Register 3104 HSP=50.0 Hz [#8, 10.0 ms]  CRC ok\n"
        "    10  2.100000000  12 request   Read Holding Registers 3201..3202 (2)  CRC ok\n"
        "    11  2.110000000  12 response  Read Holding Registers 3201..3202 (2): ETA=Ready to switch on RFR=0.2 Hz"
        " [#10, 10.0 ms]  CRC ok\n"
    )


def test_fc5_and_fc8_echo_retries(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    coil, echo = rtu("01 05 0010 FF00"), rtu("01 08 0000 A537")
    frames = [(0.0, coil), (0.5, coil), (0.51, coil), (0.6, echo), (1.1, echo), (1.11, echo), (1.2, echo)]
    out, _ = assert_same([pcap(tmp_path, frames), "--timeout", "0.4"], monkeypatch)
    assert out == (
        "     1  0.000000000   1 request   Write Single Coil 16 = ON [no response]  CRC ok\n"
        "     2  0.500000000   1 request   Write Single Coil 16 = ON  CRC ok\n"
        "     3  0.510000000   1 response  Write Single Coil 16 = ON [#2, 10.0 ms]  CRC ok\n"
        "     4  0.600000000   1 request   Diagnostics 00h Return Query Data = 42295 [no response]  CRC ok\n"
        "     5  1.100000000   1 request   Diagnostics 00h Return Query Data = 42295  CRC ok\n"
        "     6  1.110000000   1 response  Diagnostics 00h Return Query Data = 42295 [#5, 10.0 ms]  CRC ok\n"
        "     7  1.200000000   1 request   Diagnostics 00h Return Query Data = 42295 "
        "[the capture ends before any response: not known whether it was answered]  CRC ok\n"
    )


def test_a_request_sharing_its_record_and_a_late_answer_that_differs(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (an answer past the timeout that is not the request's bytes stays a late answer)
    frames = [(0.0, READ), (0.012, READ_ANSWER + HSP), (0.6, HSP), (0.612, HSP), (1.0, HSP_LOW), (1.5, HSP)]
    out, _ = assert_same([pcap(tmp_path, frames), "--profile", "atv71", "--timeout", "0.4"], monkeypatch)
    assert out == (
        "     1  0.000000000  12 request   Read Holding Registers 3201..3202 (2)  CRC ok\n"
        "     2  0.012000000  12 response  Read Holding Registers 3201..3202 (2): ETA=Ready to switch on RFR=0.2 Hz"
        " [#1, 12.0 ms]  CRC ok\n"
        "     3  0.012000000  12 request   Write Single Register 3104 HSP=50.0 Hz [no response]  CRC ok\n"
        "     4  0.600000000  12 request   Write Single Register 3104 HSP=50.0 Hz  CRC ok\n"
        "     5  0.612000000  12 response  Write Single Register 3104 HSP=50.0 Hz [#4, 12.0 ms]  CRC ok\n"
        "     6  1.000000000  12 request   Write Single Register 3104 HSP=45.0 Hz [no response]  CRC ok\n"
        "     7  1.500000000  12 response  Write Single Register 3104 HSP=50.0 Hz [no request] [warning: response"
        " 500.0 ms after request #6, later than the 400 ms timeout: not its answer]  CRC ok\n"
    )


def ascii_frame(binary: bytes) -> bytes:
    body = binary[:-2]  # (the RTU CRC off: ASCII's LRC instead)
    lrc = -sum(body) & 0xFF
    return b":" + (body + bytes([lrc])).hex().upper().encode() + b"\r\n"


def test_ascii(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    frames = [(seconds, ascii_frame(frame)) for seconds, frame in HUNTER[:5]]
    out, _ = assert_same([pcap(tmp_path, frames), "--profile", "atv71", "--timeout", "0.4", "--mode", "ascii"],
                         monkeypatch)
    assert out == "".join(line.replace("CRC ok", "LRC ok") + "\n" for line in HUNTER_LINES.splitlines()[:5])


def test_live_expiry_then_the_retry() -> None:
    # A live capture releases the request once its timeout has passed (expire): the retry that comes
    # after is still the master's retry, as the capture file reads it.
    framer, pairer = RtuFramer(), Pairer(hold=True, timeout=0.4)
    t = 1_700_000_000.0
    items = pairer.push(framer.feed(Chunk(HSP, t, boundary=True)))
    items += pairer.expire(t + 0.45)
    for seconds in (0.5, 0.512):
        items += pairer.push(framer.feed(Chunk(HSP, t + seconds, boundary=True)))
    items += pairer.push(framer.finish()) + pairer.finish()
    frames = [item for item in items if isinstance(item, Frame)]
    assert [(f.number, f.kind, f.unanswered, f.request.number if f.request else None) for f in frames] == [
        (1, Kind.REQUEST, True, None), (2, Kind.REQUEST, False, None), (3, Kind.RESPONSE, False, 2)]
