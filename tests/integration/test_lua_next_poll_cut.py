"""The plugin as vw3-decode on a request the end of the capture cuts after an answer (tests/differential/
test_next_poll_cut.py; lua/src/rtu.lua cut_request): 'no valid frame' before, 'the capture ends inside a request
(4 of 8 bytes)' now; after noise, 'no valid frame' still; an answer nobody asked for stays one. Exact fields
(tshark -2) and every field as vw3-decode says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.function", "-e", "vw3.noise.reason"]




@pytest.mark.parametrize(
    ("tail", "third"),
    [(POLL[:4], "4;;the capture ends inside a request (4 of 8 bytes)"),
     (bytes.fromhex("01 10 0000"), "4;;the capture ends inside a request (4 bytes of it)"),
     (b"\xaa\xbb" + POLL[:4], "4;;no valid frame"),  # (noise before it: nothing bounds its start)
     (rtu("01 03 02 0001"), "2;3;"),  # (an answer nobody asked for, shorter than a request)
     (rtu("01 17 04 0237 011E"), "2;23;")],  # (one cut before its request reading's byte count)
)
def test_the_next_poll_cut_after_an_answer(tail: bytes, third: str, tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "cut.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (tail, T0 + 1.0)])
    assert tshark_fields(pcap, FIELDS) == ["1;3;", "2;3;", third]
    assert_same_as_vw3_decode(pcap)
