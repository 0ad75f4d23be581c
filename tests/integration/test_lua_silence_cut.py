"""The plugin on the file live writes of a request a silence cuts (tests/differential/test_silence_cut.py): a file
closes nothing at a silence, so the bytes before it are 'no valid frame' there, never 'the capture ends inside a
request' (which live said, e33fca3, until it named the silence); the cut at the file's end keeps it. Exact fields
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


def test_a_request_a_silence_cuts(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "silence.pcap", [(POLL, T0), (ANSWER, T0 + 0.01), (POLL[:4], T0 + 1.0),
                                                  (POLL, T0 + 2.0), (ANSWER, T0 + 2.01), (POLL[:4], T0 + 3.0)])
    assert tshark_fields(pcap, FIELDS) == [
        "1;3;", "2;3;", "4;;no valid frame", "1;3;", "2;3;", "4;;the capture ends inside a request (4 of 8 bytes)"]
    assert_same_as_vw3_decode(pcap)
