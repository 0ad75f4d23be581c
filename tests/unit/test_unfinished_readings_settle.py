"""A reading whose bytes have not all come is not waited for when they would swallow a record that is a frame of
its own (framing/reach.py _crosses_framed_record), in "does an intact frame start here" (_valid_frame_at: what follows
a damaged frame, a glitch byte, a scanned frame) as in the framer's own readings (_match). Fed record by record (the
plugin's single pass, live capture), a damaged request then '0c 01 be 11' in one record (slave 12's FC1: a request
of 8 bytes, an answer of 5 + 0xbe = 195) held every later record until 195 bytes had come, past records that are
frames; so did an FC23 request's start ('0c 17 00 01': its byte count not come yet, NEED). The record after it,
a frame, settles it: noise, then the frame. damaged_stream(3051) written by -w held records 2..5 and 7..9 (tshark's
one pass: '(N bytes continue)'). Pure Python framer; the engine: tests/differential/test_unfinished_readings.py;
the plugin: tests/integration/test_lua_unfinished_readings.py."""
from __future__ import annotations

from dissector.protocol.crc import with_crc
from test_scan_reach_settles import _fed  # (records fed one by one, each a boundary)

REQUEST, ANSWER = with_crc(bytes.fromhex("0C0320D00003")), with_crc(bytes.fromhex("0C0306800000030002"))
DAMAGED = REQUEST[:-1] + bytes([REQUEST[-1] ^ 1])
COUNTER = with_crc(bytes.fromhex("0C0B"))  # (a 4-byte request: Get Comm Event Counter)


def test_a_long_reading_after_a_damaged_request_is_settled_by_the_next_record() -> None:
    got, rest = _fed([REQUEST, ANSWER, DAMAGED + bytes.fromhex("0c01be11"), REQUEST, ANSWER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                   ["noise 0c0320d000030eee0c01be11", "request 0c0320d000030eef"],
                   ["response 0c030680000003000217e4"], ["request 0c0320d000030eef"],
                   ["response 0c030680000003000217e4"]]
    assert rest == []


def test_a_reading_whose_length_has_not_come_is_settled_by_the_next_record() -> None:
    # (the FC23 request's byte count is its 11th byte: past the 4-byte request after it)
    got, rest = _fed([REQUEST, ANSWER, DAMAGED + bytes.fromhex("0c170001"), COUNTER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                   ["noise 0c0320d000030eee0c170001", f"request {COUNTER.hex()}"],
                   ["request 0c0320d000030eef"], ["response 0c030680000003000217e4"]]
    assert rest == []


def test_a_frame_start_whose_length_has_not_come_is_not_waited_for_across_a_framed_record() -> None:
    # (a record of its own, '0c 17 00 01' waited for its byte count as an FC23 request, past the request after it)
    got, rest = _fed([REQUEST, ANSWER, bytes.fromhex("0c170001"), COUNTER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                   ["noise 0c170001", f"request {COUNTER.hex()}"], ["request 0c0320d000030eef"],
                   ["response 0c030680000003000217e4"]]
    assert rest == []


# A record that is a frame of a code without a length rule (slave 12's user-defined 70), its CRC checking at the
# record's end, is a frame of its own too (_ends_record): a reading or a CRC scan before it does not reach across
# it (before: '29 46 01 02' and '0c 03 c8' held to the next record with a length rule; the FC8/00 scan whose CRC
# over both records checks read them as one Return Query Data of 16 bytes).
USER = with_crc(bytes.fromhex("0C4601020304"))
FC8 = bytes.fromhex("0c0800001234bb74")  # (its CRC register is back to its start: it and any frame check as one)


def test_a_record_that_is_a_scanned_frame_settles_what_is_before_it() -> None:
    for first in (bytes.fromhex("29460102"), FC8, bytes.fromhex("0c03c8")):
        got, rest = _fed([REQUEST, ANSWER, first, USER, REQUEST, ANSWER])
        assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                       [f"noise {first.hex()}", "request 0c46010203042817"], ["request 0c0320d000030eef"],
                       ["response 0c030680000003000217e4"]], first.hex()
        assert rest == []
