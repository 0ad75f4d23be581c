"""The plugin as vw3-decode on a frame over the spec's 256-byte ADU whose header gives its length, cut by the end of
the capture or by a silence (tests/differential/test_over_adu_cut.py; lua/src/rtu.lua cut_answer, cut_request,
lua/src/ascii.lua): 'the capture ends inside the response (200 of 257 bytes)', 'a silence cuts the response (200 of
257 bytes)', as a cut answer of 256 bytes or fewer is named. Before, 'no valid frame'. Exact fields (tshark -2) and
every field as vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.protocol.crc import lrc
from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
CHAR = 11 / 19200
WORDS = "".join(f"{k:04x}" for k in range(126))
READ_126, ANSWER_126 = rtu("01 03 0000 007e"), rtu("01 03 fc" + WORDS)  # (byte count 252: 257 bytes)
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
FC23 = rtu("01 17 0000 0001 0010 007a f4" + WORDS[: 4 * 122])  # (write 122 registers: 257 bytes)
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.noise.reason", "-e", "vw3.note"]


def test_a_long_answer_cut(tmp_path: Path) -> None:
    answer_at = T0 + 8 * CHAR + 0.005
    records = [(READ_126, T0), (ANSWER_126[:100], answer_at), (ANSWER_126[100:200], answer_at + 100 * CHAR)]
    pcap = write_pcap(tmp_path / "end.pcap", records)
    # (a record with no item of its own, its bytes shown in the next: ';;')
    assert tshark_fields(pcap, FIELDS) == [
        "1;;the capture ends inside the response (200 of 257 bytes)", ";;",
        "4;the capture ends inside the response (200 of 257 bytes);"]
    assert_same_as_vw3_decode(pcap)
    pcap = write_pcap(tmp_path / "silence.pcap", [*records, (POLL, T0 + 1.0), (ANSWER, T0 + 1.01)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;;", ";;", "4;a silence cuts the response (200 of 257 bytes);", "1;;", "2;;"]
    assert_same_as_vw3_decode(pcap)


def test_a_long_request_cut(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "request.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (FC23[:200], T0 + 0.03)])
    assert tshark_fields(pcap, FIELDS) == ["1;;", "2;;", "4;the capture ends inside a request (200 of 257 bytes);"]
    assert_same_as_vw3_decode(pcap)


def test_a_long_ascii_answer_cut(tmp_path: Path) -> None:
    def line(hex_text: str) -> bytes:
        body = bytes.fromhex(hex_text)
        return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"

    pcap = write_pcap(tmp_path / "ascii.pcap", [(line("010300000" + "07e"), T0), (line("0103fc" + WORDS)[:400], T0 + 0.05)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;;the capture ends inside the response (400 of 515 bytes)",
        "4;the capture ends inside the response (400 of 515 bytes);"]
    assert_same_as_vw3_decode(pcap)
