"""A reading that would swallow a record that is a frame of its own is none (framing/rtu.py
_crosses_framed_record), and a damaged reading whose byte count is 0 is none (_counts_nothing: every count of the
spec counts something). Fed record by record (the plugin's single pass, live capture), each record's frames come
with it or the next record, not at finish(): 'ff ff 01 b0' + a request read 'ff 01' as slave 255 FC1 whose
answer would be 181 bytes; '01 03 00 00 00' (a request cut short by its record's end) was an answer with byte
count 0 and a bad CRC, then waited for as a request of 8 bytes (tests/unit/test_cut_request_at_the_end.py: at the
end of the input). Pure Python framer; the engine and the plugin: tests/differential/
test_cut_requests.py, tests/integration/test_lua_one_pass_framed_records.py."""
from __future__ import annotations

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.protocol.crc import with_crc

REQUEST, ANSWER = with_crc(bytes.fromhex("0C0320D00003")), with_crc(bytes.fromhex("0C0306800000030002"))
ONE, ONE_ANSWER = with_crc(bytes.fromhex("010300000001")), with_crc(bytes.fromhex("0103020007"))


def _fed(records: list[bytes]) -> tuple[list[list[str]], list[str]]:
    framer = RtuFramer()
    got = [[f"{item.kind.value} {bytes(item.raw).hex()}"
            for item in framer.feed(Chunk(data, 1700000000 + index, boundary=True))]
           for index, data in enumerate(records)]
    rest = framer.finish()
    return got, [f"{item.kind.value} {bytes(item.raw).hex()} {getattr(item, 'reason', '')}" for item in rest]


def test_noise_read_as_a_long_answer_gives_up_at_a_record_that_is_a_frame() -> None:
    got, rest = _fed([REQUEST, ANSWER, bytes.fromhex("ffff01b0") + REQUEST, ANSWER, REQUEST, ANSWER])
    assert got == [["request 0c0320d000030eef"], ["response 0c030680000003000217e4"], [],
                   ["noise ffff01b0", "request 0c0320d000030eef", "response 0c030680000003000217e4"],
                   ["request 0c0320d000030eef"], ["response 0c030680000003000217e4"]]
    assert rest == []


def test_a_request_cut_by_its_record_s_end_is_noise_when_the_next_record_comes() -> None:
    got, rest = _fed([ONE, ONE[:5], ONE, ONE_ANSWER])
    assert got == [["request 010300000001840a"], [], ["noise 0103000000", "request 010300000001840a"],
                   ["response 0103020007f986"]]
    assert rest == []

