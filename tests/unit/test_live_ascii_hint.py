"""--live without --mode (hunt 55: Modbus ASCII heard live was 0 frames and noise, with no hint):
live_options.live_mode frames ASCII on a port set to 7 data bits (RTU's binary needs 8); at 8, detect.py
AsciiHeard says once, on stderr, which options decode the first bytes heard when they hold Modbus ASCII, as
heard or as a 7-bit line heard by an 8-bit UART. (app/live.py wires them in; its pty test comes with that.)"""
from __future__ import annotations

import argparse
import io

import pytest

from dissector.app.detect import AsciiHeard, ascii_heard, framings
from dissector.app.live_options import BYTESIZE_GIVEN, live_mode
from dissector.protocol.crc import lrc, with_crc


def line(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


ASCII = (line("020300000001") + line("0203020007")) * 4  # 4 reads of slave 2 and their answers: 128 bytes
RTU = (with_crc(bytes.fromhex("020300000001")) + with_crc(bytes.fromhex("0203020007"))) * 4
SEVEN_E_ONE = bytes(byte | 0x80 if bin(byte).count("1") % 2 else byte for byte in ASCII)  # (parity as bit 7)
HINT = "vw3-decode: the bytes heard hold {}, framed here as RTU: capture with {}\n"


@pytest.mark.parametrize(("mode", "bytesize", "given", "framing"), [
    (None, 8, False, None), (None, 7, True, "ascii"), (None, 8, True, None), ("rtu", 7, True, "rtu"),
    ("ascii", 8, True, "ascii"), ("ascii", 8, False, "ascii"),
])
def test_live_mode(mode: str | None, bytesize: int, given: bool, framing: str | None) -> None:
    args = argparse.Namespace(mode=mode, bytesize=bytesize, **{BYTESIZE_GIVEN: given})
    assert live_mode(args) == framing


def test_detect_tries_ascii_alone_at_seven_bits() -> None:
    assert framings(None, 7) == (("ascii", 7),) and framings(None, None) == (("rtu", 8), ("ascii", 7))


@pytest.mark.parametrize(("data", "found"), [
    (ASCII, ("ascii", 8)), (SEVEN_E_ONE, ("ascii", 7)), (RTU, None), (bytes(range(256)) * 4, None),
    (RTU + ASCII, None),  # (RTU frames came first: a file of these bytes is RTU, protocol/ascii.py sample_mode)
])
def test_ascii_heard(data: bytes, found: tuple[str, int] | None) -> None:
    assert ascii_heard(data) == found


@pytest.mark.parametrize(("data", "hint"), [
    (ASCII, HINT.format("Modbus ASCII frames with a good LRC", "--mode ascii --bytesize 8")),
    (SEVEN_E_ONE, HINT.format("Modbus ASCII frames sent with 7 data bits", "--mode ascii")),
    (RTU, ""),
])
def test_told_once_whatever_the_reads(data: bytes, hint: str) -> None:
    for size in (1, 7, 64, len(data)):
        err = io.StringIO()
        heard = AsciiHeard(err)
        for at in range(0, len(data), size):
            heard(data[at : at + size])
        heard(data, True)  # (more, then the end of the capture: told once)
        assert err.getvalue() == hint


def test_a_short_capture_is_judged_at_its_end() -> None:
    err = io.StringIO()
    heard = AsciiHeard(err)
    heard(ASCII[:32])
    assert err.getvalue() == ""  # (fewer than 64 bytes: more may come)
    heard(b"", True)
    assert err.getvalue() == HINT.format("Modbus ASCII frames with a good LRC", "--mode ascii --bytesize 8")
