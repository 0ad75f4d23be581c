"""A request the end of the capture cuts after an answer (the next poll; no answer awaited) was 'no valid frame':
it is 'the capture ends inside a request (4 of 8 bytes)', as the cut after an unanswered request already was
(0cbf5f5), from a bound only (a record's start, a silence, the end of a frame: framing/bounded.py _cut_request;
after noise, 'no valid frame' still), never where a frame of another layout starts. Exact lines, the engine and
VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x); the plugin: tests/integration/test_lua_next_poll_cut.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import assert_same, write_pcap

T0 = 1_700_000_000 * 10**9
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")


def _lines(capture: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str]]:
    """The summary and -V lines, the engine's equal to the Python stages' (--json, -x too)."""
    out, _ = assert_same([str(capture)], monkeypatch)
    verbose, _ = assert_same([str(capture), "-V"], monkeypatch)
    for option in ("--json", "-x"):
        assert_same([str(capture), option], monkeypatch)
    return out.splitlines(), verbose.splitlines()


@pytest.mark.parametrize(
    ("tail", "reason"),
    [(POLL[:4], "the capture ends inside a request (4 of 8 bytes)"),
     (POLL[:2], "the capture ends inside a request (2 of 8 bytes)"),
     (bytes.fromhex("01 10 0000 0002 04"), "the capture ends inside a request (7 of 13 bytes)"),
     (bytes.fromhex("01 10 0000"), "the capture ends inside a request (4 bytes of it)"),
     (bytes.fromhex("AA BB CC") + POLL[:4], "no valid frame")],  # (noise before it: nothing bounds its start)
)
def test_the_next_poll_cut_after_an_answer(tail: bytes, reason: str, tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "cut.bin"
    capture.write_bytes(POLL + ANSWER + tail)
    out, verbose = _lines(capture, monkeypatch)
    assert out[2] == f"     3            -   - noise     {len(tail)} bytes of noise at offset 17: {tail.hex(' ')}"
    assert f"    Reason: {reason}" in verbose
    capture = tmp_path / "cut.pcap"
    write_pcap(capture, [(POLL, T0), (ANSWER, T0 + 10**7), (tail, T0 + 10**9)])
    _, verbose = _lines(capture, monkeypatch)
    assert f"    Reason: {reason}" in verbose


@pytest.mark.parametrize(
    ("answer", "line"),
    [("01 03 02 0001", "1 response  Read Holding Registers (1): ?+0=1"),  # (7 bytes: FC3's request takes 8)
     # (9 bytes: FC23's request reading has no byte count yet)
     ("01 17 04 0237 011E", "1 response  Read/Write Multiple Registers (2): ?+0=567 ?+1=286")],
)
def test_an_answer_nobody_asked_for_at_the_end_stays_one(answer: str, line: str, tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    # (its response reading checks out: no request is cut)
    capture = tmp_path / "unasked.bin"
    capture.write_bytes(POLL + ANSWER + rtu(answer))
    out, _ = _lines(capture, monkeypatch)
    unasked = "[no request] [response without a matching request in the capture]"
    assert out[2] == f"     3            -   {line} {unasked}  CRC ok"
