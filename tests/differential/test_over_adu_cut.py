"""A frame over the spec's 256-byte ADU whose header gives its length (test_over_adu_frames: an FC3 answer of byte
count 252, 257 bytes; an FC23 request writing 122 registers, 257) cut by the end of the capture or by a silence is
named as a shorter one is: `the capture ends inside the response (200 of 257 bytes)` on its request and as the
noise's reason, `a silence cuts the response (...)`, `the capture ends inside a request (...)`. Before, the cut
applied up to 256 bytes only: the long answer was `200 bytes of noise` with reason `no valid frame` and its
request `[the capture ends before any response: not known whether it was answered]`. ASCII alike (a 515-character
line: `ASCII frame cut off by the end of the capture` before). The engine and VW3_PURE_PYTHON=1 alike; the plugin:
tests/integration/test_lua_over_adu_cut.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_next_poll_cut import _lines
from test_over_adu_frames import ANSWER, FC23, POLL, WORDS
from test_timed_summary import CHAR_NS, write_pcap

from dissector.protocol.crc import lrc

T0 = 1_700_000_000 * 10**9
READ_126, ANSWER_126 = rtu("01 03 0000 007e"), rtu("01 03 fc" + WORDS)  # (byte count 252: 257 bytes)
READ_LINE = ("     1            -   1 request   Read Holding Registers 0..125 (126) [{}] [warning: quantity 126 outside "
             "the spec's 1..125]  CRC ok")
NOISE = "     2            -   - noise     200 bytes of noise at offset 8: 01 03 fc 00 00 00 01 00 02 00 03 00 04 00 05 00…"


def test_a_long_answer_the_capture_ends_in(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.bin"
    capture.write_bytes(READ_126 + ANSWER_126[:200])
    out, verbose = _lines(capture, monkeypatch)
    assert out[:2] == [READ_LINE.format("the capture ends inside the response (200 of 257 bytes)"), NOISE]
    assert "    Reason: the capture ends inside the response (200 of 257 bytes)" in verbose


def test_a_long_answer_a_silence_cuts(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (its first 200 bytes in two records at the line's pace, then 1 s of silence and the next poll)
    capture = tmp_path / "cut.pcap"
    answer_at = T0 + 8 * CHAR_NS + 5_000_000
    write_pcap(capture, [(READ_126, T0), (ANSWER_126[:100], answer_at), (ANSWER_126[100:200], answer_at + 100 * CHAR_NS),
                         (POLL, T0 + 10**9), (ANSWER, T0 + 10**9 + 8 * CHAR_NS + 5_000_000)])
    out, verbose = _lines(capture, monkeypatch)
    assert [line[22:] for line in out] == [
        "1 request   Read Holding Registers 0..125 (126) [no response] [warning: quantity 126 outside the spec's "
        "1..125]  CRC ok",
        "- noise     200 bytes of noise at offset 8: 01 03 fc 00 00 00 01 00 02 00 03 00 04 00 05 00…",
        "1 request   Read Holding Registers 0..1 (2)  CRC ok",
        "1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#3, 9.6 ms]  CRC ok",
    ]
    assert "    Reason: a silence cuts the response (200 of 257 bytes)" in verbose


def test_a_long_request_the_capture_ends_in(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.bin"
    capture.write_bytes(POLL + ANSWER + FC23[:200])
    out, verbose = _lines(capture, monkeypatch)
    assert out[2] == ("     3            -   - noise     200 bytes of noise at offset 17: 01 17 00 00 00 01 00 10 00 7a "
                      "f4 00 00 00 01 00…")
    assert "    Reason: the capture ends inside a request (200 of 257 bytes)" in verbose


def _ascii(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


def test_a_long_ascii_answer_the_capture_ends_in(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.txt"
    capture.write_bytes(_ascii("0103 0000 007e".replace(" ", "")) + _ascii("0103fc" + WORDS)[:400])
    out, verbose = _lines(capture, monkeypatch)
    assert out[0].endswith("Read Holding Registers 0..125 (126) [the capture ends inside the response (400 of 515 "
                           "bytes)] [warning: quantity 126 outside the spec's 1..125]  LRC ok")
    assert "    Reason: the capture ends inside the response (400 of 515 bytes)" in verbose
