"""The plugin as vw3-decode on frames longer than the spec's 256-byte ADU whose header gives their length, their CRC
good (tests/differential/test_over_adu_frames.py; lua/src/rtu.lua match, frame_at, ends_record; lua/src/ascii.lua
long_line): an FC23 request writing 122 registers (257 bytes), an FC16 request with byte count 250 (259), an FC3
answer with byte count 252 (257) were noise ('no valid frame'), where tshark's mbrtu decodes them. Exact fields
(tshark -2), every field as vw3-decode says it, and tshark's mbrtu on the same records: the same function and
fields. ASCII lines over 513 characters with a good LRC alike."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from dissector.protocol.crc import lrc
from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import ensure_tool, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
WORDS = "".join(f"{k:04x}" for k in range(126))
FC23 = rtu("01 17 0000 0001 0010 007a f4" + WORDS[: 4 * 122])
FC23_ANSWER = rtu("01 17 02 0007")
FC16 = rtu("01 10 0000 007d fa" + WORDS[: 4 * 125])
FC16_ANSWER = rtu("01 10 0000 007d")
READ_126, ANSWER_126 = rtu("01 03 0000 007e"), rtu("01 03 fc" + WORDS)
LOOKALIKE = bytes.fromhex("01 10 0000 007d fa" + WORDS[: 4 * 125]) + b"\x12\x34"  # (its CRC bad: noise)
POLL = rtu("01 03 0000 0002")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.function", "-e", "vw3.start", "-e",
          "vw3.quantity", "-e", "vw3.byte_count", "-e", "vw3.warning"]
OVER = "frame length {} above the spec's 256-byte ADU (its header gives it)"
ROWS = [
    f"1;23;0;1;244;{OVER.format(257)},write quantity 122 outside the spec's 1..121",
    "2;23;0;1;2;",
    f"1;16;0;125;250;{OVER.format(259)},quantity 125 outside the spec's 1..123",
    "2;16;0;125;;",
    "1;3;0;126;;quantity 126 outside the spec's 1..125",
    f"2;3;0;126;252;{OVER.format(257)}",
]


def _mbrtu(pcap: Path) -> list[str]:
    """tshark's own Modbus RTU dissector on the records: function, reference, word and byte counts."""
    tshark = ensure_tool("tshark", "tshark")
    command = [tshark, "-n", "-r", str(pcap), "-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""',
               "-T", "fields", "-E", "separator=;", "-e", "mbrtu.unit_id", "-e", "modbus.func_code", "-e",
               "modbus.reference_num", "-e", "modbus.word_cnt", "-e", "modbus.byte_cnt"]
    return subprocess.run(command, capture_output=True, text=True, timeout=300).stdout.splitlines()


def test_long_frames_are_frames(tmp_path: Path) -> None:
    frames = [FC23, FC23_ANSWER, FC16, FC16_ANSWER, READ_126, ANSWER_126]
    pcap = write_pcap(tmp_path / "long.pcap", [(frame, T0 + k * 0.3) for k, frame in enumerate(frames)])
    assert tshark_fields(pcap, FIELDS) == ROWS
    # (mbrtu: the function of each, FC16's and FC3's counts as the plugin's; FC23's request it shows by its code)
    assert _mbrtu(pcap) == ["1;23;;;", "1;23;;;", "1;16;0;125;250", "1;16;0;125;", "1;3;0;126;", "1;3;;;252"]
    assert_same_as_vw3_decode(pcap)
    # (one record: its items one packet, tshark's occurrences of each field joined; the lookalike noise as before)
    pcap = write_pcap(tmp_path / "stream.pcap", [(b"".join(frames) + LOOKALIKE + POLL, T0)])
    over = [OVER.format(257), "write quantity 122 outside the spec's 1..121", OVER.format(259),
            "quantity 125 outside the spec's 1..123", "quantity 126 outside the spec's 1..125", OVER.format(257)]
    assert tshark_fields(pcap, FIELDS + ["-e", "vw3.noise.reason"]) == [
        "1,2,1,2,1,2,4,1;23,23,16,16,3,3,3;0,0,0,0,0,0,0;1,1,125,125,126,126,2;244,2,250,252;" + ",".join(over)
        + ";no valid frame"]
    assert_same_as_vw3_decode(pcap)


def _ascii(frame: bytes) -> bytes:
    body = frame[:-2]
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


def test_long_ascii_lines_are_frames(tmp_path: Path) -> None:
    bad = _ascii(FC16)[:-4] + b"00\r\n"  # (its LRC wrong: noise, as before)
    lines = [_ascii(POLL), _ascii(FC23), _ascii(FC23_ANSWER), bad]
    pcap = write_pcap(tmp_path / "long.pcap", [(line, T0 + k / 2) for k, line in enumerate(lines)])  # (515: 268 ms)
    long = "frame length 515 above the spec's 513 characters (its header gives it)"
    assert tshark_fields(pcap, FIELDS + ["-e", "vw3.noise.reason"]) == [
        "1;3;0;2;;;",
        f"1;23;0;1;244;{long},write quantity 122 outside the spec's 1..121;",
        "2;23;0;1;2;;",
        "4,4;;;;;;no CR LF within 513 characters of the ':',outside an ASCII frame",
    ]
    assert_same_as_vw3_decode(pcap)
