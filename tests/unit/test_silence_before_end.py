"""What cuts the bytes a framer holds at the end of a timed capture (StreamFramer.finish_at, hunt66b): the line silent
t3.5 from its last bytes to the tap's last record (a file's record of no byte at live's stop: Source.recorded_until)
cuts them, as a silence cuts them before the next bytes and as live closes them at one; shorter, the capture's end.
Before, the decode of live's -w file said 'the capture ends inside the response (3 of 11 bytes)' of bytes live said
'a silence cuts the response (3 of 11 bytes)' of (tests/differential/test_silence_before_stop.py: live, the engine)."""
from __future__ import annotations

import pytest

from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame, Noise, Stamp
from dissector.pipeline import dissect
from dissector.protocol.crc import lrc

REQUEST = bytes.fromhex("07 03 00 00 00 03 05 ad")
CUT = bytes.fromhex("07 03 06")
T0 = 1_000_000_000_000
MS = 1_000_000
WITHIN = "the capture ends {} ms after the request, within the 1000 ms timeout: not known whether it was answered"
BY_THE_END = "the capture ends inside the response (3 of 11 bytes)"


def _decode(end_us: int, baud: int = 19200) -> tuple[list[str], str]:
    """The request's notes and the noise's reason, the tap recording until `end_us` after the cut bytes came."""
    chunks = [Chunk(REQUEST, Stamp(T0), True), Chunk(CUT, Stamp(T0 + 50 * MS), True)]
    items = list(dissect(chunks, framer=RtuFramer(baud), timeout=1.0,
                         recorded=lambda: Stamp(T0 + 50 * MS + end_us * 1000)))
    request, noise = items
    assert isinstance(request, Frame) and isinstance(noise, Noise)
    return request.notes, noise.reason


def test_a_silence_recorded_through_cuts_the_answer() -> None:
    assert _decode(400_000) == ([WITHIN.format("450.0")], "a silence cuts the response (3 of 11 bytes)")


@pytest.mark.parametrize(("end_us", "baud", "cut"), [
    (3_700, 19200, False), (3_800, 19200, True),  # 3 bytes: 1.719 ms; t3.5: 2.005 ms
    (7_400, 9600, False), (7_500, 9600, True),  # 3.438 ms; 4.010 ms
    (2_000, 115200, False), (2_100, 115200, True),  # 0.286 ms; 1.750 ms, fixed above 19200 baud
])
def test_t35_at_the_line_speed(end_us: int, baud: int, cut: bool) -> None:
    notes, reason = _decode(end_us, baud)
    if cut:
        assert (notes, reason) == ([WITHIN.format(f"{50 + end_us / 1000:.1f}")],
                                   "a silence cuts the response (3 of 11 bytes)")
    else:
        assert (notes, reason) == ([BY_THE_END], BY_THE_END)


def test_no_record_after_the_bytes() -> None:
    """A file that ends with the cut bytes: the end cuts them."""
    chunks = [Chunk(REQUEST, Stamp(T0), True), Chunk(CUT, Stamp(T0 + 50 * MS), True)]
    items = list(dissect(chunks, timeout=1.0, recorded=lambda: Stamp(T0 + 50 * MS)))
    assert [item.notes if isinstance(item, Frame) else item.reason for item in items] == [[BY_THE_END], BY_THE_END]


def test_no_silence_cuts_an_ascii_line() -> None:
    body = bytes.fromhex("010300000001")
    read = b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"
    chunks = [Chunk(read, Stamp(T0), True), Chunk(b":010302", Stamp(T0 + 50 * MS), True)]
    items = list(dissect(chunks, framer=AsciiFramer(), timeout=1.0, recorded=lambda: Stamp(T0 + 500 * MS)))
    cut = "the capture ends inside the response (7 of 15 bytes)"
    assert [item.notes if isinstance(item, Frame) else item.reason for item in items] == [[cut], cut]
