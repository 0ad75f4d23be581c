"""Record ends and silences as the framer keeps them (framing/offsets.py): a sorted set it asks for the first
after a point and those in a window, where a scan of them all made random bytes read one byte a record (a USB
tap, a line at the wrong speed) cost 6.4 ms a byte (bench/noise_throughput.py --kind random-reads). The decode
is unchanged (tests/differential: noise, silences, record ends)."""
from __future__ import annotations

import random

from dissector.framing.offsets import Offsets
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk


def test_one_byte_records_of_noise_are_all_noise() -> None:
    data = random.Random(5).randbytes(600)
    framer = RtuFramer()
    items = []
    for index, byte in enumerate(data):
        items += framer.feed(Chunk(bytes([byte]), 1_700_000_000 + index / 1000, boundary=True))
    items += framer.finish()
    assert b"".join(bytes(item.raw) for item in items) == data  # (every byte an item's, in order)


def test_offsets_answer_as_a_sorted_set() -> None:
    offsets = Offsets()
    offsets.update([10, 4, 7, 7, 20])
    assert list(offsets) == [4, 7, 10, 20] and 7 in offsets and 8 not in offsets
    again = Offsets()
    again.update([4, 20, 10, 7])
    assert offsets == again and offsets != Offsets() and repr(again) == "Offsets([4, 7, 10, 20])"
    assert offsets.first_after(4, 9) == 7 and offsets.first_after(7, 9) is None and offsets.first_after(0, 4) == 4
    assert offsets.within(7, 20) == [7, 10] and offsets.within(21, 30) == []
    offsets.drop_below(8)
    assert list(offsets) == [10, 20] and 7 not in offsets and bool(offsets)
    offsets.drop_below(21)
    assert not offsets
