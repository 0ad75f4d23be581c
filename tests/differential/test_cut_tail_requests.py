"""A request cut by the end of the capture after a request awaiting its answer was read as that answer when
its third byte passed for a byte count: '0C 03 20 D0' (the next poll's first bytes) after a read of 3
registers of slave 12 showed 'the capture ends inside the response (4 of 37 bytes)', 0x20 read as a byte count
of 32, on the request and as the noise's reason; ':0C0320D0' in ASCII '(9 of 75 bytes)'. The request implies
an answer of 11 bytes (framing/answers.py): a response reading of another length is none, the bytes are the
request reading (framing/rules.py Awaiting._not_the_answer). A tail that can be the answer stays one. Exact
lines, the engine and VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x); the plugin:
tests/integration/test_lua_cut_tail_requests.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.framing.answers import answer_length
from dissector.model import Frame, Kind
from dissector.protocol.crc import lrc
from helpers import rtu
from test_timed_summary import assert_same, write_pcap

POLL, ANSWER = rtu("0C 03 20D0 0003"), rtu("0C 03 06 0001 0002 0003")
T0 = 1_700_000_000 * 10**9
READ = "     1  0.000000000  12 request   Read Holding Registers 8400..8402 (3)"
UNKNOWN = ("[the capture ends 1000.0 ms after the request, within the 1000 ms timeout: not known whether it"
           " was answered]")


def _lines(capture: Path, monkeypatch: pytest.MonkeyPatch, *options: str) -> tuple[list[str], list[str]]:
    """The summary and -V lines, the engine's equal to the Python stages' (-V, --json, -x too)."""
    out, _ = assert_same([str(capture), *options], monkeypatch)
    verbose, _ = assert_same([str(capture), *options, "-V"], monkeypatch)
    for option in (["--json"], ["-x"]):
        assert_same([str(capture), *options, *option], monkeypatch)
    return out.splitlines(), verbose.splitlines()


def _ascii(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text.replace(" ", ""))
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


def test_the_next_poll_cut_after_an_unanswered_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.pcap"
    write_pcap(capture, [(POLL, T0), (POLL[:4], T0 + 10**9)])
    out, verbose = _lines(capture, monkeypatch)
    noise = "     2  1.000000000   - noise     4 bytes of noise at offset 8: 0c 03 20 d0"
    assert out == [f"{READ} {UNKNOWN}  CRC ok", noise]
    assert "    Reason: the capture ends inside a request (4 of 8 bytes)" in verbose


def test_raw_bytes_too(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.bin"
    capture.write_bytes(POLL + POLL[:3])
    out, verbose = _lines(capture, monkeypatch)
    assert out == [
        "     1            -  12 request   Read Holding Registers 8400..8402 (3) [the capture ends before any"
        " response: not known whether it was answered]  CRC ok",
        "     2            -   - noise     3 bytes of noise at offset 8: 0c 03 20",
    ]
    assert "    Reason: the capture ends inside a request (3 of 8 bytes)" in verbose


def test_an_answer_cut_stays_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "answer.pcap"
    write_pcap(capture, [(POLL, T0), (ANSWER[:5], T0 + 10**7)])
    out, verbose = _lines(capture, monkeypatch)
    cut = "the capture ends inside the response (5 of 11 bytes)"
    noise = "     2  0.010000000   - noise     5 bytes of noise at offset 8: 0c 03 06 00 01"
    assert out == [f"{READ} [{cut}]  CRC ok", noise]
    assert f"    Reason: {cut}" in verbose
    capture.write_bytes(POLL + bytes.fromhex("0C 83"))
    out, _ = _lines(capture, monkeypatch)
    assert "[the capture ends inside the exception response (2 of 5 bytes)]" in out[0]


def test_the_next_poll_after_an_answer_is_no_answer(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "answered.pcap"
    write_pcap(capture, [(POLL, T0), (ANSWER, T0 + 10**7), (POLL[:4], T0 + 10**9)])
    out, verbose = _lines(capture, monkeypatch)
    assert out[2] == "     3  1.000000000   - noise     4 bytes of noise at offset 19: 0c 03 20 d0"
    # (nothing awaited: no reading of an answer; the request's, from the answer's end: framing/bounded.py)
    assert "    Reason: the capture ends inside a request (4 of 8 bytes)" in verbose


def test_ascii(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.asc"
    capture.write_bytes(_ascii("0C 03 20D0 0003") + b":0C0320D0")
    out, verbose = _lines(capture, monkeypatch, "--mode", "ascii")
    assert out == [
        "     1            -  12 request   Read Holding Registers 8400..8402 (3) [the capture ends before any"
        " response: not known whether it was answered]  LRC ok",
        "     2            -   - noise     9 bytes of noise at offset 17: 3a 30 43 30 33 32 30 44 30",
    ]
    assert "    Reason: the capture ends inside a request (9 of 17 bytes)" in verbose
    capture.write_bytes(_ascii("0C 03 20D0 0003") + b":0C03060001")
    out, _ = _lines(capture, monkeypatch, "--mode", "ascii")
    assert "[the capture ends inside the response (11 of 23 bytes)]" in out[0]


@pytest.mark.parametrize(
    ("request_hex", "length"),
    [("0C 03 20D0 0003", 11), ("0C 04 0000 007D", 255), ("0C 01 0000 000A", 7), ("0C 02 0000 0008", 6),
     ("0C 17 0000 0002 0010 0001 02 0000", 9), ("0C 06 0000 0001", None), ("0C 10 0000 0001 02 0000", None)],
)
def test_the_answer_length_a_request_implies(request_hex: str, length: int | None) -> None:
    raw = rtu(request_hex)
    request = Frame(0, raw, None, Kind.REQUEST, raw[0], raw[1], 0, 0)
    assert answer_length(request) == length


def test_a_request_typed_without_its_crc_after_one(monkeypatch: pytest.MonkeyPatch) -> None:
    # (--hex asks the framer whether short bytes are an answer cut: '0C 03 20 D0 00 03' was 6 of 37 bytes of one,
    # noise; it is the request typed without its CRC, which --hex appends)
    out, _ = assert_same(["--hex", POLL.hex(" "), "--hex", "0C 03 20 D0 00 03"], monkeypatch)
    assert out.splitlines()[1] == (
        "     2            -  12 request   Read Holding Registers 8400..8402 (3) [the capture ends before any response:"
        " not known whether it was answered] [no CRC typed: append 0E EF (CRC 0xEF0E)]  CRC computed (none typed)"
    )
