"""The plugin on a frame cut by a silence, then the stop (tests/differential/test_silence_before_stop.py): the line
silent t3.5 from its last bytes to the capture's last record (live -w's record of no byte at the stop) cuts them,
'a silence cuts the response (3 of 11 bytes)', and the request waited to then, not known whether answered, as live
and vw3-decode say (it said 'the capture ends inside the response (3 of 11 bytes)' on both: vw3.records finish,
silent_at_end in lua/src/stream.lua); shorter than t3.5, or on an ASCII line, the end cuts them. Exact fields
(tshark -2), the tree's line, and every field as vw3-decode says it, at the edge of t3.5 too."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import run_tshark, write_pcap

from dissector.protocol.crc import lrc

pytestmark = pytest.mark.integration

T0 = 1700000000.0
REQUEST, CUT = rtu("07 03 0000 0003"), bytes.fromhex("07 03 06")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.noise.reason", "-e", "vw3.note"]
WITHIN = "the capture ends {} ms after the request, within the 1000 ms timeout: not known whether it was answered"
BY_THE_END = "the capture ends inside the response (3 of 11 bytes)"
BY_A_SILENCE = "a silence cuts the response (3 of 11 bytes)"


def test_a_silence_then_the_stop(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "stop.pcap", [(REQUEST, T0), (CUT, T0 + 0.05), (b"", T0 + 0.5)])
    assert tshark_fields(pcap, FIELDS) == [f"1;;{WITHIN.format('500.0')}", f"4;{BY_A_SILENCE};", ";;"]
    tree = run_tshark(pcap, "-V", "-Y", "frame.number == 2").stdout.splitlines()
    assert f"VW3 noise, 3 bytes: {BY_A_SILENCE}" in tree
    assert_same_as_vw3_decode(pcap)


# t3.5 is 2.005 ms at 19200 baud; the 3 bytes take 1.719 ms from their record's time: 1.98 ms, 2.08 ms of silence.
@pytest.mark.parametrize(("after", "said"), [(0.0037, BY_THE_END), (0.0038, BY_A_SILENCE)])
def test_the_edge_of_t35(tmp_path: Path, after: float, said: str) -> None:
    pcap = write_pcap(tmp_path / "edge.pcap", [(REQUEST, T0), (CUT, T0 + 0.05), (b"", T0 + 0.05 + after)])
    note = said if said == BY_THE_END else WITHIN.format(f"{(0.05 + after) * 1000:.1f}")
    assert tshark_fields(pcap, FIELDS) == [f"1;;{note}", f"4;{said};", ";;"]
    assert_same_as_vw3_decode(pcap)


def test_the_cut_after_a_silence_inside_then_the_stop(tmp_path: Path) -> None:
    """Two pieces of a request, each after a silence, then the stop: a silence cuts both (stream.py's flag was
    reset by the first cut: 'the capture ends inside a request (3 of 8 bytes)' on the second)."""
    poll, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    pcap = write_pcap(tmp_path / "two.pcap", [(poll, T0), (answer, T0 + 0.01), (poll[:2], T0 + 1.0),
                                              (poll[:3], T0 + 2.0), (b"", T0 + 2.5)])
    assert [line.split(";")[1] for line in tshark_fields(pcap, FIELDS)][2:4] == [
        "a silence cuts a request (2 of 8 bytes)", "a silence cuts a request (3 of 8 bytes)"]
    assert_same_as_vw3_decode(pcap)


def test_an_ascii_line_cut_then_a_silence_then_the_stop(tmp_path: Path) -> None:
    body = bytes.fromhex("010300000001")
    read = b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"
    pcap = write_pcap(tmp_path / "ascii.pcap", [(read, T0), (b":010302", T0 + 0.05), (b"", T0 + 0.5)])
    cut = "the capture ends inside the response (7 of 15 bytes)"
    assert tshark_fields(pcap, FIELDS) == [f"1;;{cut}", f"4;{cut};", ";;"]
    assert_same_as_vw3_decode(pcap)
