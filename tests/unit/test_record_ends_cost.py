"""Input read one byte a record (a USB tap, a line at the wrong speed) is framed in work linear in its size with
a small factor: a record end's answer (framing/reach.py _record_end: does a frame end where that record does?)
is kept while more bytes cannot change it, not asked again of every record end ahead for each byte (100 KB of
`2b 0e` a byte a record took 70 s through the Python stages). A count of work, not a timing; the output is the
one the framer gave before (the differential and plugin parity tests hold it)."""
from __future__ import annotations

import pytest

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Noise


def framed_one_byte_records(data: bytes, monkeypatch: pytest.MonkeyPatch) -> tuple[list, int]:
    """The items of `data` fed a byte a record, and how many times a frame start's interpretations were asked."""
    asked = 0
    interpretations = RtuFramer._interpretations

    def counting(self: RtuFramer, buf: bytearray, i: int) -> tuple:
        nonlocal asked
        asked += 1
        return interpretations(self, buf, i)

    monkeypatch.setattr(RtuFramer, "_interpretations", counting)
    framer = RtuFramer()
    items = []
    for k, byte in enumerate(data):
        items += framer.feed(Chunk(bytes([byte]), 1_700_000_000 + k / 1000, True))
    items += framer.finish()
    return items, asked


@pytest.mark.parametrize("pattern", ["2b0e", "0e2b", "2b0e2b0e0e"])
def test_one_byte_records_of_a_pattern_cost_little_a_byte(pattern: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: 2,000 bytes of `2b 0e` asked 468,368 interpretations (234 a byte: the record ends ahead, for each
    byte); now 22,835 (11 a byte). Every byte is in one item, in order."""
    data = (bytes.fromhex(pattern) * 2000)[:2000]
    items, asked = framed_one_byte_records(data, monkeypatch)
    assert b"".join(item.raw for item in items) == data
    assert asked < 40 * len(data), asked
    assert any(isinstance(item, Noise) for item in items)
