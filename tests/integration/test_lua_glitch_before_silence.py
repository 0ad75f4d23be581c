"""The plugin on timed captures of 1 to 3 glitch bytes before a silence (tests/differential/
test_glitch_before_silence.py): it says what live and vw3-decode say, 'too short for a frame' (it said 'no valid
frame': no_frame, add_skipped in lua/src/stream.lua). Exact fields (tshark -2), the tree's line, and every field as
vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.function", "-e", "vw3.noise.reason"]


def test_a_glitch_run_before_a_silence(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "glitch.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (b"\xff\xff", T0 + 0.5),
                                                 (POLL, T0 + 1.0), (ANSWER, T0 + 1.01)])
    assert tshark_fields(pcap, FIELDS) == ["1;3;", "2;3;", "4;;too short for a frame", "1;3;", "2;3;"]
    tree = run_tshark(pcap, "-V", "-Y", "frame.number == 3").stdout.splitlines()
    at = tree.index("VW3 noise, 2 bytes: too short for a frame")
    assert tree[at + 4] == "    [Why noise: too short for a frame]"
    assert_same_as_vw3_decode(pcap)


def test_stretches_between_silences_and_a_frame_s_record(tmp_path: Path) -> None:
    """Glitch bytes in the answer's record; then bytes no frame starts at across silences, each stretch its own
    reason (one skip in the framer)."""
    pcap = write_pcap(tmp_path / "stretches.pcap", [
        (POLL, T0), (ANSWER + b"\xff", T0 + 0.01), (bytes.fromhex("fefe"), T0 + 0.3),
        (bytes.fromhex("fefefefe"), T0 + 0.5), (b"\xfe", T0 + 0.7), (POLL, T0 + 1.0), (ANSWER, T0 + 1.01)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;3;", "2,4;3;too short for a frame", "4;;too short for a frame", "4;;no valid frame",
        "4;;too short for a frame", "1;3;", "2;3;"]
    assert_same_as_vw3_decode(pcap)
