"""A record's end settles what waits for bytes past it (framing/reach.py _ends_record; framing/rtu.py _scan, _match's damaged
frames): fed record by record, the framer gives each record's frame with that record, as the plugin's single
pass shows it (tests/integration/test_lua_one_pass_records.py, test_lua_one_pass_bad_crc.py), after a
broadcast request (00: a glitch byte before a 'slave 6, FC12' answer of 134 bytes?), an exception from slave 0
('slave 144, FC2'), FC8/00 (a CRC scan) and an answer with a bad CRC (a frame inside it crossing the record's
end?). Record by record as live capture and the pcap reader feed them: the pure Python framer."""
from __future__ import annotations

import pytest

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.protocol.crc import with_crc

REQUEST, ANSWER = with_crc(bytes.fromhex("0C0320D00003")), with_crc(bytes.fromhex("0C03068000000300 02".replace(" ", "")))
BAD = ANSWER[:-1] + bytes([ANSWER[-1] ^ 1])  # (its CRC's high byte one bit off: E5 for E4)


def _fed(records: list[bytes]) -> tuple[list[list[bytes]], list[bytes]]:
    """Each record's frames as the framer gives them when the record is fed, and what finish() gives."""
    framer = RtuFramer()
    got = [[bytes(item.raw) for item in framer.feed(Chunk(data, 1700000000 + index, boundary=True))]
           for index, data in enumerate(records)]
    return got, [bytes(item.raw) for item in framer.finish()]


@pytest.mark.parametrize("odd", ["00060C810001", "009002", "0C0800001234"])
def test_each_record_s_frame_comes_with_it(odd: str) -> None:
    records = [REQUEST, ANSWER, with_crc(bytes.fromhex(odd)), REQUEST, ANSWER]
    assert _fed(records) == ([[data] for data in records], [])


def test_a_bad_crc_answer_that_is_its_record_comes_with_it() -> None:
    # (before: held until finish(), every later record with it: a frame from byte 4, '00 03 ...', may have
    # crossed the record's end)
    records = [REQUEST, BAD, REQUEST, ANSWER]
    assert _fed(records) == ([[REQUEST], [BAD], [REQUEST], [ANSWER]], [])


def test_a_bad_crc_answer_after_its_request_comes_with_the_next_record_s_frame() -> None:
    # A record that starts with the request does not say the answer is a record's frame: the next record,
    # a frame, does. (before: held until finish())
    records = [REQUEST + BAD, REQUEST, ANSWER]
    assert _fed(records) == ([[REQUEST], [BAD, REQUEST], [ANSWER]], [])


def test_a_bad_crc_frame_in_a_usb_read_still_gives_way_to_an_intact_frame_crossing_its_end() -> None:
    # A read that starts inside noise and ends where a cut answer (3 registers, 9 bytes) would: the intact
    # request crossing the read's end is found (a record's end alone is no frame's end: reads end anywhere)
    request = with_crc(bytes.fromhex("0C0300000001"))
    cut = bytes.fromhex("0C0304") + request
    records = [REQUEST, b"\xfa" + cut[:9], cut[9:] + ANSWER]  # (FA: a reserved address, noise)
    got, rest = _fed(records)
    assert [frame for frames in got for frame in frames] + rest == [REQUEST, b"\xfa\x0c\x03\x04", request, ANSWER]


def test_live_reads_a_bad_crc_answer_comes_with_the_frame_after_it() -> None:
    # Live capture's reads end no record (a read is no frame: a USB adapter's), but a silence of t3.5 (the
    # next read's time) is a boundary (stream.py feed): the frame after the answer ends at one (_ends_record).
    # (before: held until the capture thread's flush after a long silence, every later frame with it)
    framer = RtuFramer()
    reads = [(REQUEST, 0.0), (BAD, 0.01), (REQUEST, 2.0), (ANSWER, 2.01), (REQUEST, 4.0)]
    got = [[bytes(item.raw) for item in framer.feed(Chunk(data, 1700000000 + time))] for data, time in reads]
    assert got == [[REQUEST], [], [], [BAD, REQUEST, ANSWER], [REQUEST]]
    assert framer.finish() == []
