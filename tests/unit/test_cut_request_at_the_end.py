"""A damaged reading whose byte count is 0 is none (framing/rtu.py _counts_nothing: every count of the spec counts
something): '01 03 00 00 00', a request cut short by the end of the capture, was an answer with byte count 0 and a
bad CRC. At the end of the input such bytes are a request cut by it: the noise says so. Pure Python framer; the
engine and the plugin: tests/differential/test_cut_requests.py, tests/integration/test_lua_cut_requests.py."""
from __future__ import annotations

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.protocol.crc import with_crc

ONE = with_crc(bytes.fromhex("010300000001"))


def test_at_the_end_a_request_cut_short_is_said_so() -> None:
    framer = RtuFramer()
    assert framer.feed(Chunk(ONE, 1700000000.0, boundary=True))[0].raw == ONE
    assert framer.feed(Chunk(ONE[:5], 1700000001.0, boundary=False)) == []
    [noise] = framer.finish()
    assert (noise.raw, noise.reason) == (ONE[:5], "the capture ends inside a request (5 of 8 bytes)")


def test_a_byte_count_of_0_with_a_bad_crc_is_no_answer() -> None:
    framer = RtuFramer()
    framer.feed(Chunk(ONE, 1700000000.0, boundary=True))
    items = framer.feed(Chunk(bytes.fromhex("0103000000") + ONE, 1700000001.0, boundary=True)) + framer.finish()
    assert [(item.kind.value, bytes(item.raw).hex()) for item in items] == [
        ("noise", "0103000000"), ("request", ONE.hex())]
