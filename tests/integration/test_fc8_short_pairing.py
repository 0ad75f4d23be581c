"""One pairing rule for FC8 frames too short for their sub-function (malformed), in vw3-decode (engine and
VW3_PURE_PYTHON=1) and the plugin: an answer's echo of its request ([pairing] echo: the sub-function) is weighed
over the bytes of it both frames hold (decode/pairing.py _same_echo, lua/src/pairing.lua same_echo, the
framer's _awaited and lua/src/layouts.lua await_echo alike). A frame that holds none of it pairs by its slave
and function, as every malformed frame does (an FC3 request too short for its quantity is answered) and as
tshark's mbrtu pairs (unit and function alone).
- 01 08 / 01 08 00 (10 ms apart): vw3-decode said `[no response]` and `[no request] [response without a matching
  request]` (the echo check then compared b"" with b"\\x00"); the plugin paired them. Now both pair them.
- 01 08 00 / 01 08 01: they disagree on the byte both hold: vw3-decode's framer read the second as the master's
  next request; the plugin's (await_echo kept no echo for a request too short for it) read it as the answer and
  paired it. Now both read two requests."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1700000000.0
RECORDS = [(rtu("01 08"), T0), (rtu("01 08 00"), T0 + 0.01), (rtu("01 08 00"), T0 + 0.5), (rtu("01 08 01"), T0 + 0.51)]
SHORT = "disagrees with the spec's layout (8 bytes), its CRC good] [warning: malformed"
LINES = [
    f"     1     0.000000   1 request   Diagnostics (malformed) [warning: frame length 4 {SHORT} request: too short "
    "for subfunction]  CRC ok",
    f"     2     0.010000   1 response  Diagnostics (malformed) [#1, 10.0 ms] [warning: frame length 5 {SHORT} "
    "response: too short for subfunction]  CRC ok",
    f"     3     0.500000   1 request   Diagnostics (malformed) [no response] [warning: frame length 5 {SHORT} "
    "request: too short for subfunction]  CRC ok",
    "     4     0.510000   1 request   Diagnostics (malformed) [the capture ends before any response: not known "
    f"whether it was answered] [warning: frame length 5 {SHORT} request: too short for subfunction]  CRC ok",
]


@pytest.fixture()
def capture(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "fc8.pcap", RECORDS)


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_pairs_by_what_both_hold(capture: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(capture), "-n"])
    assert (status, err) == (0, "")
    assert out.splitlines() == LINES
    status, out, err = run_cli([str(capture), "-n", "-T", "fields", "-e", "kind", "-e", "request_frame",
                                "-e", "response_frame"])
    assert out.splitlines() == ["request\t\t2", "response\t1\t", "request\t\t", "request\t\t"]


def test_the_plugin_pairs_alike(capture: Path) -> None:
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-e", "_ws.col.Info", "-e", "vw3.request_frame",
                     "-e", "vw3.response_frame")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [
        "1 Diagnostics request (malformed)||2", "1 Diagnostics response (malformed)|1|",
        "1 Diagnostics request (malformed)||", "1 Diagnostics request (malformed)||",
    ]
