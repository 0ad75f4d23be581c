"""A CRC scan does not reach across a record that is a frame of its own (framing/reach.py _framed_reach): fed record
by record (the plugin's single pass, live capture), each record's frames come with it or the next record, not at
finish(). '29 46' after a request in its record (slave 41's user-defined function 70: no length rule, a CRC scan)
waited for up to MAX_ADU bytes for a CRC match, past the records after it that are frames: every later record
was held to the end of the input; so was a damaged request before it, whose end a frame starting there
would confirm (_valid_frame_at's scan). Pure Python framer; the plugin: tests/integration/test_lua_scan_reach.py."""
from __future__ import annotations

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.protocol.crc import with_crc

REQUEST, ANSWER = with_crc(bytes.fromhex("0C0320D00003")), with_crc(bytes.fromhex("0C0306800000030002"))
OTHER = with_crc(bytes.fromhex("0C0320D10001"))
SCAN = bytes.fromhex("29460102")


def _fed(records: list[bytes]) -> tuple[list[list[str]], list[str]]:
    framer = RtuFramer()
    got = [[f"{item.kind.value} {bytes(item.raw).hex()}"
            for item in framer.feed(Chunk(data, 1700000000 + index, boundary=True))]
           for index, data in enumerate(records)]
    return got, [f"{item.kind.value} {bytes(item.raw).hex()}" for item in framer.finish()]


def test_a_scan_after_a_request_gives_up_at_a_record_that_is_a_frame() -> None:
    got, rest = _fed([REQUEST, ANSWER, OTHER + SCAN, REQUEST, ANSWER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], ["request 0c0320d10001deee"],
                   ["noise 29460102", "request 0c0320d000030eef"], ["response 0c030680000003000217e4"],
                   ["request 0c0320d000030eef"], ["response 0c030680000003000217e4"]]
    assert rest == []


def test_a_damaged_request_before_a_scan_start_is_settled_by_the_next_record() -> None:
    # (whether the damaged request ends where a frame starts: the scan from '29 46' waited for up to 256 bytes,
    # _valid_frame_at; no frame ends before the next record, a frame of its own)
    damaged = REQUEST[:-1] + bytes([REQUEST[-1] ^ 1])
    got, rest = _fed([REQUEST, ANSWER, damaged + SCAN, REQUEST, ANSWER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                   ["noise 0c0320d000030eee29460102", "request 0c0320d000030eef"],
                   ["response 0c030680000003000217e4"], ["request 0c0320d000030eef"],
                   ["response 0c030680000003000217e4"]]
    assert rest == []
