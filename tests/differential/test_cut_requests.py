"""A request cut short (a pcap record the capture ends inside, or a record of its first bytes) was read as an
answer with byte count 0 and a bad CRC: '01 03 00 00 00' after '01 03 0000 0001' showed 'response Read Holding
Registers 0: [warning: byte count 0 disagrees with the registers asked (1)] CRC BAD (received 0x0000...)'. A
reading with a bad CRC whose byte count is 0 is none (framing/rtu.py _counts_nothing): at the end of the capture
the bytes are noise whose reason says a request is cut, and before a silence that the silence cuts it (as live says).
Exact lines, engine and VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import assert_same, write_pcap

ONE, ONE_ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")
T0 = 1_700_000_000 * 10**9
READ = "     1  0.000000000   1 request   Read Holding Registers 0"
NOISE = "     2  1.000000000   - noise     5 bytes of noise at offset 8: 01 03 00 00 00"


def _outputs(capture: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str]]:
    out, _ = assert_same([str(capture)], monkeypatch)
    verbose, _ = assert_same([str(capture), "-V"], monkeypatch)
    for option in (["--json"], ["-x"]):
        assert_same([str(capture), *option], monkeypatch)
    return out.splitlines(), verbose.splitlines()


def test_a_record_the_capture_ends_inside(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.pcap"
    write_pcap(capture, [(ONE, T0), (ONE, T0 + 10**9)])
    capture.write_bytes(capture.read_bytes()[:-3])
    out, verbose = _outputs(capture, monkeypatch)
    assert out == [
        f"{READ} [the capture ends 1000.0 ms after the request, within the 1000 ms timeout: not known whether it was"
        " answered]  CRC ok",
        NOISE,
        "vw3-decode: warning: record 2 is cut short: 5 of 8 bytes (the capture ends inside it); the bytes that are"
        " there are decoded",
    ]
    assert "    Reason: the capture ends inside a request (5 of 8 bytes)" in verbose


def test_a_record_of_a_request_s_first_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "short.pcap"
    write_pcap(capture, [(ONE, T0), (ONE[:5], T0 + 10**9), (ONE, T0 + 2 * 10**9),
                         (ONE_ANSWER, T0 + 2 * 10**9 + 10**7)])
    out, verbose = _outputs(capture, monkeypatch)
    assert out == [
        f"{READ} [no response]  CRC ok",
        NOISE,
        "     3  2.000000000   1 request   Read Holding Registers 0  CRC ok",
        "     4  2.010000000   1 response  Read Holding Registers 0: 0=7 [#3, 10.0 ms]  CRC ok",
    ]
    assert "    Reason: a silence cuts a request (5 of 8 bytes)" in verbose  # (as live says: test_silence_cut.py)
