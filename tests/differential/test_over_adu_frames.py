"""Frames longer than the spec's 256-byte ADU whose header gives their length, their CRC good (framing/rules.py
MAX_COUNTED, protocol/table.py LONGEST_COUNTED: what a one-byte count can say, FC23's 13 + 255): an FC23 request
writing 122 registers (257 bytes), an FC16 request with byte count 250 (259), an FC3 answer with byte count 252
from a non-conformant device (257). They were '257 bytes of noise' where tshark's mbrtu decodes them; now a frame
with the warning over_adu, and the quantity's from the decoder. A byte count saying 250 without a good CRC is
noise as before, and costs bounded work. ASCII alike (over_ascii: a line over 513 characters with a good LRC).
Exact lines, the engine and VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x); the plugin and tshark's mbrtu:
tests/integration/test_lua_over_adu_frames.py."""
from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from dissector.framing import rtu as rtu_framer
from dissector.framing import rules
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame
from dissector.protocol.crc import lrc
from helpers import rtu
from test_timed_summary import CHAR_NS, assert_same, write_pcap
from test_next_poll_cut import _lines

T0 = 1_700_000_000 * 10**9
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
WORDS = "".join(f"{k:04x}" for k in range(126))
FC23 = rtu("01 17 0000 0001 0010 007a f4" + WORDS[: 4 * 122])  # (write 122 registers at 16: 257 bytes)
FC23_ANSWER = rtu("01 17 02 0007")
FC16 = rtu("01 10 0000 007d fa" + WORDS[: 4 * 125])  # (125 registers, byte count 250: 259 bytes)
FC16_ANSWER = rtu("01 10 0000 007d")
READ_126, ANSWER_126 = rtu("01 03 0000 007e"), rtu("01 03 fc" + WORDS)  # (byte count 252: 257 bytes)
# A byte count of 250 whose CRC is bad: noise, as before
LOOKALIKE = bytes.fromhex("01 10 0000 007d fa" + WORDS[: 4 * 125]) + b"\x12\x34"

OVER = "[warning: frame length {} above the spec's 256-byte ADU (its header gives it)]"
FC23_LINE = ("1 request   Read/Write Multiple Registers read 0, write 16=0 17=1 18=2 19=3 20=4 21=5 … (+116) "
             + OVER.format(257) + " [warning: write quantity 122 outside the spec's 1..121]  CRC ok")
FC16_LINE = ("1 request   Write Multiple Registers 0..124 (125): 0=0 1=1 2=2 3=3 4=4 5=5 … (+119) "
             + OVER.format(259) + " [warning: quantity 125 outside the spec's 1..123]  CRC ok")
READ_LINE = "1 request   Read Holding Registers 0..125 (126) [warning: quantity 126 outside the spec's 1..125]  CRC ok"
ANSWER_LINE = ("1 response  Read Holding Registers 0..125 (126): 0=0 1=1 2=2 3=3 4=4 5=5 … (+120) [#{}] "
               + OVER.format(257) + "  CRC ok")


def test_long_frames_in_a_raw_stream(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "long.bin"
    capture.write_bytes(POLL + ANSWER + FC23 + FC23_ANSWER + FC16 + FC16_ANSWER + READ_126 + ANSWER_126 + POLL)
    out, verbose = _lines(capture, monkeypatch)
    assert [line[22:] for line in out[2:]] == [
        FC23_LINE,
        "1 response  Read/Write Multiple Registers 0: 0=7 [#3]  CRC ok",
        FC16_LINE,
        "1 response  Write Multiple Registers 0..124 (125) written [#5]  CRC ok",
        READ_LINE,
        ANSWER_LINE.format("7"),
        "1 request   Read Holding Registers 0..1 (2) [the capture ends before any response: not known whether it was"
        " answered]  CRC ok",
    ]
    assert "    Warning: frame length 259 above the spec's 256-byte ADU (its header gives it)" in verbose


def test_long_frames_a_record_each(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "long.pcap"
    frames = [FC23, FC23_ANSWER, FC16, FC16_ANSWER, READ_126, ANSWER_126]
    write_pcap(capture, [(frame, T0 + k * 3 * 10**8) for k, frame in enumerate(frames)])  # (257 bytes: 147 ms at 19200)
    out, verbose = _lines(capture, monkeypatch)
    assert out[0] == "     1  0.000000000   " + FC23_LINE
    assert out[2] == "     3  0.600000000   " + FC16_LINE
    assert out[5] == "     6  1.500000000   " + ANSWER_LINE.format("5, 300.0 ms")
    assert "    Warning: frame length 257 above the spec's 256-byte ADU (its header gives it)" in verbose
    # (bytes cut by USB reads: the same frames; a record's end inside a long frame is no bound of it)
    stream = b"".join(frames)
    write_pcap(capture, [(stream[at : at + 64], T0 + at * CHAR_NS) for at in range(0, len(stream), 64)])
    cut, _ = _lines(capture, monkeypatch)
    paired = [re.sub(r"\[#(\d), [^]]+\]", r"[#\1]", line[22:]) for line in out]
    assert [re.sub(r"\[#(\d), [^]]+\]", r"[#\1]", line[22:]) for line in cut] == paired


def test_a_long_header_with_a_bad_crc_is_noise_as_before(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "lookalike.bin"
    capture.write_bytes(POLL + ANSWER + LOOKALIKE + POLL + ANSWER)
    out, _ = _lines(capture, monkeypatch)
    assert out[2:] == [
        "     3            -   - noise     259 bytes of noise at offset 17: 01 10 00 00 00 7d fa 00 00 00 01 00 02 00"
        " 03 00…",
        "     4            -   1 request   Read Holding Registers 0..1 (2)  CRC ok",
        "     5            -   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#4]  CRC ok",
    ]


def test_long_headers_in_noise_cost_bounded_work(monkeypatch: pytest.MonkeyPatch) -> None:
    """Noise of long headers (byte count 250, CRC bad) and random bytes: the bytes the framer's CRCs read stay
    within a few frames' worth a byte (10.2 before, 11.8 now: 268 bytes a header at most, not the buffer), the
    same items as noise. (A guard: it passes before the change too.)"""
    hashed = [0]
    crc16 = rules.crc16

    def counting(data: bytes) -> int:
        hashed[0] += len(data)
        return crc16(data)

    monkeypatch.setattr(rules, "crc16", counting)
    monkeypatch.setattr(rtu_framer, "crc16", counting)
    rng = random.Random(5)
    data = b"".join(LOOKALIKE[:7] + rng.randbytes(254) for _ in range(200)) + POLL
    framer = RtuFramer()
    items = framer.feed(Chunk(data)) + framer.finish()
    assert hashed[0] < 16 * len(data)
    frames = [item for item in items if type(item) is Frame]  # (what random bytes pass by chance, as before)
    assert not any(len(frame.raw) > rules.MAX_ADU or frame.offset % 261 == 0 for frame in frames[:-1])
    assert frames[-1].raw == POLL


def _ascii(frame: bytes) -> bytes:
    body = frame[:-2]
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


def test_long_ascii_lines(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "long.asc"
    bad = _ascii(FC16)[:-4] + b"00\r\n"  # (its LRC wrong: no line end within 513 characters, as before)
    capture.write_bytes(_ascii(POLL) + _ascii(ANSWER) + _ascii(FC23) + _ascii(FC23_ANSWER) + bad + _ascii(POLL))
    out, verbose = _lines(capture, monkeypatch)
    long = "[warning: frame length 515 above the spec's 513 characters (its header gives it)]"
    assert out[2] == ("     3            -   1 request   Read/Write Multiple Registers read 0, write 16=0 17=1 18=2"
                      f" 19=3 20=4 21=5 … (+116) {long} [warning: write quantity 122 outside the spec's 1..121]"
                      "  LRC ok")
    assert out[3] == "     4            -   1 response  Read/Write Multiple Registers 0: 0=7 [#3]  LRC ok"
    assert out[4:6] == [
        "     5            -   - noise     513 bytes of noise at offset 566: 3a 30 31 31 30 30 30 30 30 30 30 37 44 46"
        " 41 30…",
        "     6            -   - noise     6 bytes of noise at offset 1079: 37 43 30 30 0d 0a",
    ]
    assert "    Reason: no CR LF within 513 characters of the ':'" in verbose
    assert out[6] == ("     7            -   1 request   Read Holding Registers 0..1 (2) [the capture ends before any"
                      " response: not known whether it was answered]  LRC ok")
    assert "    Warning: " + long[10:-1] in verbose


def test_a_long_frame_typed_without_its_crc(monkeypatch: pytest.MonkeyPatch) -> None:
    # (its length is its header's: the CRC to append is said, as for a frame within the ADU; rules.spans_a_frame)
    out, _ = assert_same(["--hex", FC23[:-2].hex()], monkeypatch)
    assert out.splitlines() == [
        "     1            -   1 request   Read/Write Multiple Registers read 0, write 16=0 17=1 18=2 19=3 20=4"
        " 21=5 … (+116) [the capture ends before any response: not known whether it was answered] [no CRC typed:"
        f" append {FC23[-2]:02X} {FC23[-1]:02X} (CRC 0x{FC23[-1]:02X}{FC23[-2]:02X})] " + OVER.format(257)
        + " [warning: write quantity 122 outside the spec's 1..121]  CRC computed (none typed)"]
