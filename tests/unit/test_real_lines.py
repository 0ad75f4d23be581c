"""Framing what a real RS-485 tap records (issue 26): glitch bytes around frames, a byte count that
disagrees with its quantity, an answer cut by the end of the capture, garbage after a good frame, a
good request whose answer is damaged, reserved addresses. Each case is a real sequence or a manual's
frame, checked as the user sees it (summary lines) and as raw bytes, a pcap of bursts and lines."""
from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame, Kind
from dissector.render.pcapwriter import PcapWriter
from helpers import decode, hx, rtu, run_cli

# The turn-around glitches of the issue: a bus driver leaves 00 after each request, FE after each
# response (two reads of 1000..1001 and 1002..1003 by slave 1).
GLITCHED = hx(
    "01 03 03 E8 00 02 44 7B 00 01 03 04 52 66 57 07 75 66 FE "
    "01 03 03 EA 00 02 E5 BB 00 01 03 04 A4 71 46 2C BA A5 FE"
)
GLITCHED_LINES = [
    "     1            -   1 request   Read Holding Registers 1000..1001 (2)  CRC ok",
    "     2            -   - noise     1 byte of noise at offset 8: 00",
    "     3            -   1 response  Read Holding Registers 1000..1001 (2): 1000=21094 1001=22279 [#1]  CRC ok",
    "     4            -   - noise     1 byte of noise at offset 18: fe",
    "     5            -   1 request   Read Holding Registers 1002..1003 (2)  CRC ok",
    "     6            -   - noise     1 byte of noise at offset 27: 00",
    "     7            -   1 response  Read Holding Registers 1002..1003 (2): 1002=42097 1003=17964 [#5]  CRC ok",
    "     8            -   - noise     1 byte of noise at offset 37: fe",
]


def summary(*argv: str, stdin: bytes = b"") -> list[str]:
    status, out, err = run_cli([*argv, "-n"], stdin=stdin)
    assert status == 0, err
    return out.splitlines()


def signature(items: list[dict]) -> list[tuple[str, str, bool | None]]:
    return [(item["kind"], item["raw"], item.get("crc_ok")) for item in items]


@pytest.mark.parametrize("pure", [False, True])
def test_turn_around_glitches_give_two_pairs_and_four_noise_bytes(monkeypatch, pure: bool) -> None:
    if pure:
        monkeypatch.setenv("VW3_PURE_PYTHON", "1")
    assert summary("--hex", GLITCHED.hex(" ")) == GLITCHED_LINES
    assert summary("-", stdin=GLITCHED) == GLITCHED_LINES  # raw bytes: the compiled path's input


def test_turn_around_glitches_on_both_sides_and_of_every_shape() -> None:
    request, response = rtu("07 04 0010 0003"), rtu("07 04 06 0001 0002 0003")
    for before, after in [(b"\x00", b"\xfe"), (b"\xff", b"\x00\x00"), (b"\xf8\xfe", b"\xc0"), (b"\x80", b"\xff\xff\xff")]:
        stream = before + request + after + before + response + after
        frames = [item for item in decode(stream * 3) if item["kind"] != "noise"]
        assert [(item["kind"], bytes.fromhex(item["raw"])) for item in frames] == [
            ("request", request), ("response", response)] * 3, (before, after)


def test_split_anywhere_the_glitched_line_gives_the_same_items() -> None:
    stream = GLITCHED * 4
    whole = decode(stream)
    rng = random.Random(26)
    for _ in range(50):
        cuts = sorted(rng.sample(range(1, len(stream)), rng.randint(1, 12)))
        framer = RtuFramer()
        items = []
        for a, b in zip([0, *cuts], [*cuts, len(stream)]):
            items += framer.feed(Chunk(stream[a:b]))
        items += framer.finish()
        assert [(item.offset, item.raw) for item in items] == [
            (item["offset"], bytes.fromhex(item["raw"])) for item in whole]


def test_fc16_request_whose_byte_count_disagrees_with_its_quantity() -> None:
    """Altivar 212 manual: the drive answers exception 03 to a request with byte count 3 for 2 registers."""
    assert summary("--hex", "01 10 18 70 00 02 03 C4 00 17 70 D8 6F", "--hex", "01 90 03 0C 01") == [
        "     1            -   1 request   Write Multiple Registers 6256..6257 (2): 6256=50176 "
        "[warning: byte count 3 disagrees with the quantity 2] [warning: unexpected bytes after the data (1)]  CRC ok",
        "     2            -   1 exception Write Multiple Registers: exception 3 (Illegal Data Value) [#1]  CRC ok",
    ]
    # The same bytes as a raw stream: the quantity's length (13) is the frame, not noise.
    items = decode(hx("01 10 18 70 00 02 03 C4 00 17 70 D8 6F 01 90 03 0C 01"))
    assert signature(items) == [("request", "01101870000203c4001770d86f", True), ("exception", "0190030c01", True)]


def test_fc15_and_fc23_requests_framed_by_their_quantity_too() -> None:
    coils = rtu("11 0F 0013 000A 01 CD01")  # 10 coils need 2 bytes; the count says 1
    read_write = rtu("11 17 0000 0002 0010 0001 04 00FF")  # 1 register written, byte count says 4
    answer = rtu("11 17 04 0001 0002")
    items = decode(coils + rtu("11 0F 0013 000A") + read_write + answer)
    assert [(item["kind"], item["crc_ok"]) for item in items] == [
        ("request", True), ("response", True), ("request", True), ("response", True)]
    assert "byte count 1 disagrees with the quantity 10" in items[0]["warnings"]
    assert bytes.fromhex(items[2]["raw"]) == read_write and items[3]["request_frame"] == 3


def test_a_response_cut_by_the_end_of_the_capture() -> None:
    assert summary("--hex", "14 04 00 34 00 02 32 C0", "--hex", "14 04 04 14 00 00 FA 7D") == [
        "     1            -  20 request   Read Input Registers 52..53 (2) "
        "[the capture ends inside the response (8 of 9 bytes)]  CRC ok",
        "     2            -   - noise     8 bytes of noise at offset 8: 14 04 04 14 00 00 fa 7d",
    ]
    items = decode(hx("14 04 00 34 00 02 32 C0 14 04 04 14 00 00 FA 7D"))
    assert signature(items) == [("request", "14040034000232c0", True), ("noise", "14040414000 0fa7d".replace(" ", ""), None)]
    assert items[1]["reason"] == "the capture ends inside the response (8 of 9 bytes)"
    assert items[0]["notes"] == ["the capture ends inside the response (8 of 9 bytes)"]
    # An exception cut after 3 of its 5 bytes.
    items = decode(hx("14 04 00 34 00 02 32 C0 14 84 02"))
    assert items[1]["reason"] == "the capture ends inside the exception response (3 of 5 bytes)"


def test_a_good_frame_followed_by_garbage_is_kept() -> None:
    frame, garbage = hx("11 03 00 6B 00 03 76 87"), hx("20 54 54 FF")
    expected = [("request", frame.hex(), True), ("noise", garbage.hex(), None)]
    assert signature(decode(frame + garbage)) == expected
    assert signature(decode(hx("FE") + frame + garbage))[1:] == expected  # after a glitch
    # After garbage that is no glitch: its fields speak for it (a read of 3 registers).
    assert signature(decode(hx("55 12") + frame + garbage))[1:] == expected
    assert summary("--hex", "11 03 00 6B 00 03 76 87", "--hex", "20 54 54 FF")[1] == (
        "     2            -   - noise     4 bytes of noise at offset 8: 20 54 54 ff")


def test_an_intact_request_is_kept_though_its_answer_is_damaged() -> None:
    request = rtu("05 06 0100 1234")
    answer = bytearray(rtu("05 06 0100 1234"))
    answer[4] ^= 0x40
    items = decode(hx("47 A1 33") + request + bytes(answer) + hx("13 77"))
    assert [(item["kind"], item.get("crc_ok")) for item in items][:2] == [("noise", None), ("request", True)]
    assert bytes.fromhex(items[1]["raw"]) == request
    # At the end of the capture, the damaged answer is shown as such.
    items = decode(hx("47 A1 33") + request + bytes(answer))
    assert [(item["kind"], item.get("crc_ok")) for item in items] == [("noise", None), ("request", True), ("response", False)]


def test_reserved_addresses_are_framed_with_a_warning() -> None:
    lines = summary("--hex", "FE 03 00 00 00 01 90 05", "--hex", "FE 03 02 00 07 ED 92")
    assert lines == [
        "     1            - 254 request   Read Holding Registers 0 "
        "[warning: slave address 254 is reserved (248..255 are no device's)]  CRC ok",
        "     2            - 254 response  Read Holding Registers 0: 0=7 [#1] "
        "[warning: slave address 254 is reserved (248..255 are no device's)]  CRC ok",
    ]
    items = decode(rtu("FF 03 0000 0001") + rtu("FF 03 02 0007"))
    assert [(item["kind"], item["slave"], item["crc_ok"]) for item in items] == [("request", 255, True), ("response", 255, True)]


def test_glitch_bytes_invent_no_reserved_slave() -> None:
    # A glitch byte is a reserved address too: only a good CRC makes it one, never a damaged layout.
    items = decode(rtu("01 03 0000 0004") + hx("FE E0 3C FF 1F") + rtu("01 03 0000 0004"))
    assert [item["kind"] for item in items] == ["request", "noise", "request"]


def _pcap(path: Path, records: list[bytes]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, data in enumerate(records):
            writer.write(data, 1_700_000_000 + index * 0.004)
    return path


def frames_of(*argv: str, stdin: bytes = b"") -> list[tuple[str, int, str]]:
    status, out, err = run_cli([*argv, "--json", "-n"], stdin=stdin)
    assert status == 0, err
    return [(item["kind"], item["offset"], item["raw"]) for item in map(json.loads, out.splitlines())]


def test_glitched_line_as_a_pcap_of_random_bursts_and_as_a_hex_dump(tmp_path: Path) -> None:
    stream = GLITCHED * 20
    expected = frames_of("-", stdin=stream)
    assert [kind for kind, _, _ in expected].count("request") == 40
    assert [kind for kind, _, _ in expected].count("response") == 40
    assert [kind for kind, _, _ in expected].count("noise") == 80
    rng = random.Random(5)
    for bursts_count in (10, 60, 150):
        cuts = sorted(rng.sample(range(1, len(stream)), bursts_count))
        bursts = [stream[a:b] for a, b in zip([0, *cuts], [*cuts, len(stream)])]
        assert frames_of(str(_pcap(tmp_path / "bursts.pcap", bursts))) == expected
        dump = tmp_path / "line.txt"
        dump.write_text("\n".join(burst.hex(" ") for burst in bursts) + "\n")
        assert frames_of(str(dump)) == expected


def test_a_silence_between_timed_chunks_is_a_boundary() -> None:
    """A FC7 response whose CRC ends in 00 also checks as a 4-byte request: a silence after it (t3.5
    at 19200 baud is 2 ms) tells, as a record boundary does."""
    response = rtu("01 07 41")
    framer = RtuFramer()
    assert framer.feed(Chunk(response, 1.0)) == []
    (frame,) = framer.feed(Chunk(rtu("01 07"), 1.5))[:1]
    assert isinstance(frame, Frame) and (frame.kind, frame.raw) == (Kind.RESPONSE, response)
