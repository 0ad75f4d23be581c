"""Live closes a partial frame after max(t3.5, 250 ms) of silence (app/live_capture.py long_silence), the
line's rule the decode of its -w file applies (timing.silence_before, silence67): below about 154 baud t3.5 is
the longer, and live closed a partial frame after 250 ms where the file holds it until 770 ms at 50 baud."""
from __future__ import annotations

import pytest

from dissector.app.live import live_framer
from dissector.app.live_capture import CaptureThread, Handoff, long_silence, silence_threshold
from dissector.model import Chunk, Stamp

PART = bytes.fromhex("07 03 06")  # three bytes of an answer: a partial frame the framer holds


@pytest.mark.parametrize(("baud", "long", "short"), [(50, 0.77, 0.77), (150, 0.256667, 0.256667),
                                                    (9600, 0.25, 0.02), (19200, 0.25, 0.02), (115200, 0.25, 0.02)])
def test_silences_by_baud(baud: int, long: float, short: float) -> None:
    assert long_silence(baud) == pytest.approx(long, abs=1e-6)
    assert silence_threshold(baud) == pytest.approx(short, abs=1e-6)


def _holding(baud: int) -> CaptureThread:
    framer = live_framer("rtu", baud)
    assert framer.feed(Chunk(PART, Stamp(1_000_000_000_000), True)) == []
    return CaptureThread(None, framer, None, Handoff(), silence_threshold(baud),  # type: ignore[arg-type]
                         silence_long=long_silence(baud))


def test_a_slow_line_holds_a_partial_frame_through_250_ms() -> None:
    capture = _holding(50)
    assert not capture.flush_due(0.300, tried=True)
    assert capture.flush_due(0.780, tried=True)


def test_a_usual_line_closes_it_after_250_ms() -> None:
    capture = _holding(19200)
    assert not capture.flush_due(0.200, tried=True)
    assert capture.flush_due(0.260, tried=True)
