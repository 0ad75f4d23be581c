"""Modbus ASCII: framing, LRC, classification by the RTU length rules, noise, mode detection."""
from __future__ import annotations

import random

import pytest

from dissector.framing.ascii import AsciiFramer
from dissector.protocol.ascii import MAX_ASCII, detect_mode
from dissector.model import Chunk, Frame, Kind, Noise, Register
from dissector.pipeline import Dissector
from helpers import hx


def lrc_reference(data: bytes) -> int:
    return (0x100 - sum(data) % 0x100) % 0x100


def ascii_frame(hex_text: str, check: int | None = None) -> bytes:
    """`:` + hex pairs + LRC + CR LF for slave + PDU given in hex."""
    body = hx(hex_text)
    check = lrc_reference(body) if check is None else check
    return b":" + (body + bytes([check])).hex().upper().encode() + b"\r\n"


def run(data: bytes, splits: list[int] | None = None) -> list:
    dissector = Dissector(framer=AsciiFramer())
    items = []
    cuts = [0, *(splits or []), len(data)]
    for start, stop in zip(cuts, cuts[1:]):
        items += dissector.feed(Chunk(data[start:stop], float(start)))
    return items + dissector.finish()


def shape(items: list) -> list[tuple]:
    return [
        (i.offset, i.raw, i.kind, i.slave, i.function, i.crc, i.crc_expected, i.time)
        if isinstance(i, Frame) else (i.offset, i.raw, "noise", i.reason, i.time)
        for i in items
    ]


def test_lrc_vectors() -> None:
    assert ascii_frame("02 06 23 29 00 0A") == b":02062329000AA2\r\n"
    assert ascii_frame("01 06 04 05 12 34") == b":010604051234AA\r\n"


def test_write_single_register_9001() -> None:
    [frame] = run(b":02062329000AA2\r\n")
    assert isinstance(frame, Frame)
    assert (frame.mode, frame.kind, frame.slave, frame.function) == ("ascii", Kind.REQUEST, 2, 6)
    assert (frame.crc, frame.crc_expected, frame.crc_ok) == (0xA2, 0xA2, True)
    assert frame.raw == b":02062329000AA2\r\n"
    assert frame.raw_binary == hx("02 06 23 29 00 0A A2")
    assert frame.pdu == hx("06 23 29 00 0A")
    assert (frame.start, frame.quantity) == (9001, 1)
    assert frame.registers == [Register(9001, 10)]
    assert frame.warnings == []


def test_protection_story_pairs_and_decodes() -> None:
    request = ascii_frame("0C 03 20 D0 00 03")
    data = (request + ascii_frame("0C 03 06 80 00 00 03 00 02")
            + request + ascii_frame("0C 03 06 80 00 80 00 00 02")
            + request + ascii_frame("0C 83 02"))
    items = run(data)
    assert [(i.kind, i.slave, i.function, i.crc_ok) for i in items] == [
        (Kind.REQUEST, 12, 3, True), (Kind.RESPONSE, 12, 3, True),
        (Kind.REQUEST, 12, 3, True), (Kind.RESPONSE, 12, 3, True),
        (Kind.REQUEST, 12, 3, True), (Kind.EXCEPTION, 12, 3, True)]
    assert [i.request.number for i in items[1::2]] == [1, 3, 5]
    assert [(r.address, r.value) for r in items[1].registers] == [(8400, 0x8000), (8401, 3), (8402, 2)]
    assert [(r.address, r.value) for r in items[3].registers] == [(8400, 0x8000), (8401, 0x8000),
                                                                  (8402, 2)]
    assert items[5].exception_code == 2
    assert items[2].offset == len(request) + len(ascii_frame("0C 03 06 80 00 00 03 00 02"))


def test_echo_function_after_request_is_its_response() -> None:
    items = run(b":02062329000AA2\r\n" * 2)
    assert [i.kind for i in items] == [Kind.REQUEST, Kind.RESPONSE]
    assert items[1].request is items[0]


def test_bad_lrc_is_a_damaged_frame() -> None:
    [frame] = run(ascii_frame("02 06 23 29 00 0A", check=0xA3))
    assert isinstance(frame, Frame)
    assert (frame.kind, frame.crc, frame.crc_expected, frame.crc_ok) == (Kind.REQUEST, 0xA3, 0xA2, False)


def test_noise_cases_each_with_its_reason() -> None:
    good = ascii_frame("0C 03 20 D0 00 03")
    parts = [
        b"xx",
        b":0C0320D0",  # cut short by the next ':'
        good,
        b":0C0320D000030\r\n",  # odd number of digits
        b":0C0320D00003FE\n",  # LF without CR: a frame, with a warning
        ascii_frame("0C 03 20 D0"),  # too short for the answer awaited: a frame all the same, its LRC good
        ascii_frame("F8 03 20 D0 00 03"),  # slave 248: a frame (the decoder warns: reserved)
        ascii_frame("0C 03 20 D0 00 03", check=0),
        b":0C03",  # the capture ends
    ]
    data = b"".join(parts)
    offsets = [sum(len(p) for p in parts[:k]) for k in range(len(parts))]
    items = run(data)
    assert shape(items) == [
        (offsets[0], b"xx", "noise", "outside an ASCII frame", 0.0),
        (offsets[1], parts[1], "noise", "ASCII frame cut short by the next ':'", 0.0),
        (offsets[2], good, Kind.REQUEST, 12, 3, 0xFE, 0xFE, 0.0),
        (offsets[3], parts[3], "noise", "ASCII frame is not made of hex pairs", 0.0),
        (offsets[4], parts[4], Kind.REQUEST, 12, 3, 0xFE, 0xFE, 0.0),
        (offsets[5], parts[5], Kind.RESPONSE, 12, 3, 0x01, 0x01, 0.0),
        (offsets[6], parts[6], Kind.REQUEST, 248, 3, 0x12, 0x12, 0.0),
        (offsets[7], parts[7], Kind.REQUEST, 12, 3, 0x00, 0xFE, 0.0),
        # (the answer awaited to the request before, as far as it came: tests/unit/test_ascii_line_ends.py)
        (offsets[8], b":0C03", "noise", "the capture ends inside the response (5 bytes of it)", 0.0),
    ]


def test_no_lf_within_the_longest_frame() -> None:
    data = b":" + b"0" * (MAX_ASCII + 10) + ascii_frame("0C 83 02")
    items = run(data)
    assert shape(items) == [
        (0, data[:MAX_ASCII], "noise", f"no CR LF within {MAX_ASCII} characters of the ':'", 0.0),
        (MAX_ASCII, b"0" * 11, "noise", "outside an ASCII frame", 0.0),
        (MAX_ASCII + 11, ascii_frame("0C 83 02"), Kind.EXCEPTION, 12, 3, 0x6F, 0x6F, 0.0),
    ]


def test_lower_case_digits_are_flagged() -> None:
    [frame] = run(b":02062329000aa2\r\n")
    assert isinstance(frame, Frame) and frame.crc_ok
    assert frame.registers == [Register(9001, 10)]
    assert frame.warnings == ["lower-case hex digits (the spec wants upper case)"]


def test_times_come_from_the_chunk_holding_the_colon() -> None:
    first, second = ascii_frame("0C 03 20 D0 00 03"), ascii_frame("0C 83 02")
    items = run(first + second, splits=[5, len(first) + 1])
    assert [(i.offset, i.time) for i in items] == [(0, 0.0), (len(first), 5.0)]


def test_split_does_not_matter() -> None:
    data = (b"\x00garbage" + ascii_frame("0C 03 20 D0 00 03") + ascii_frame("0C 03 06 80 00 00 03 00 02")
            + b":0C0320" + ascii_frame("02 2B 0E 01 00") + ascii_frame("02 06 23 29 00 0A", check=1)
            + b"\r\n:" + b"7" * 600 + ascii_frame("0C 83 02") + b":0C")
    whole = [entry[:-1] for entry in shape(run(data))]
    byte_by_byte = [entry[:-1] for entry in shape(run(data, splits=list(range(1, len(data)))))]
    assert byte_by_byte == whole
    generator = random.Random(4)
    for _ in range(20):
        splits = sorted(generator.sample(range(1, len(data)), 12))
        assert [entry[:-1] for entry in shape(run(data, splits=splits))] == whole
    assert [i.kind for i in run(data) if isinstance(i, Frame)] == [
        Kind.REQUEST, Kind.RESPONSE, Kind.REQUEST, Kind.REQUEST, Kind.EXCEPTION]


def test_long_noise_is_cut_at_the_same_places_whatever_the_split() -> None:
    data = b"\x01" * 9000
    for splits in ([], [1000, 4096, 4097], list(range(500, 9000, 500))):
        items = run(data, splits=splits)
        assert [(i.offset, len(i.raw)) for i in items] == [(0, 4096), (4096, 4096), (8192, 808)]
        assert all(isinstance(i, Noise) for i in items)


@pytest.mark.parametrize(
    ("sample", "mode"),
    [
        (b":02062329000AA2\r\n:0206", "ascii"),
        (b"\r\n:0C8302" + b"6F\r\n", "ascii"),
        (hx("0C 03 20 D0 00 03 0E EF 0C 03 06 80 00 00 03 00 02 17 E4"), "rtu"),
        (hx("3A 03 30 31 32 33 34 35 36 37 38 39 41 42 43 44 45 46 3A 00 FF 00 FF 10"), "rtu"),
        (b":", "rtu"),
        (b":ZZ\r\n", "rtu"),
        (b"", "rtu"),
    ],
)
def test_detect_mode(sample: bytes, mode: str) -> None:
    assert detect_mode(sample) == mode


def test_lines_that_lost_their_cr_are_frames_with_a_warning() -> None:
    """A Modbus ASCII log copied through a tool that drops CRs: every line still a frame."""
    request, response = ascii_frame("01 03 00 00 00 02"), ascii_frame("01 03 04 00 0A 00 14")
    items = run(request.replace(b"\r", b"") + response.replace(b"\r", b""))
    assert [(item.kind, item.slave, item.crc_ok) for item in items] == [(Kind.REQUEST, 1, True), (Kind.RESPONSE, 1, True)]
    assert all(item.warnings == ["line ends with LF without CR (the spec ends a frame with CR LF)"] for item in items)
