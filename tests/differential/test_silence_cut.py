"""Live closes what the framer holds at a silence (live_capture.CaptureThread.step, livepath.LivePath._flush:
StreamFramer.finish(silence=True)), and the capture goes on. A request or an answer cut there was 'the capture
ends inside a request (4 of 8 bytes)' (e33fca3, 0cbf5f5), false: the next poll followed. It is 'a silence cuts a
request (4 of 8 bytes)' ('a silence cuts the response (5 of 9 bytes)'); 'the capture ends' stays where the
capture ends. Tapes of live reads (VW3_LIVE_REPLAY) decoded by the engine's live path and VW3_PURE_PYTHON=1's,
exact lines. A file with timestamps (the pcap of those reads) says what live says (it said 'no valid frame':
framing/bounded.py _silence_cut; more in test_silence_cut_files.py), the plugin too
(tests/integration/test_lua_silence_cut.py)."""
from __future__ import annotations

import json
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT
from helpers import rtu
from live_tape import tape_of
from test_timed_summary import write_pcap

from dissector.app.live_capture import _TAPE_EVENT

POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
T0 = 1_700_000_000 * 10**9
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def live(tape: Path, pure: bool, *options: str) -> list[str]:
    """vw3-decode --live's lines on a tape's reads."""
    env = dict(os.environ, VW3_LIVE_REPLAY=str(tape), PYTHONPATH=str(ROOT))
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    command = [sys.executable, "-m", "dissector", "--live", "/dev/ttyTAPE", "--baud", "19200", *options]
    run = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stdout.splitlines()


def noise_reasons(lines: list[str]) -> list[str]:
    return [item["reason"] for item in map(json.loads, lines) if item["kind"] == "noise"]


@ENGINES
def test_a_silence_cuts_the_next_poll(pure: bool, tmp_path: Path) -> None:
    tape = tmp_path / "poll.tape"
    tape.write_bytes(tape_of([(POLL, 100.0), (ANSWER, 100.01), (POLL[:4], 101.0), (POLL, 102.0),
                              (ANSWER, 102.01)], random.Random(1)))
    out = live(tape, pure, "-n")
    assert out[2] == "     3     1.000096   - noise     4 bytes of noise at offset 17: 01 03 00 00"
    assert noise_reasons(live(tape, pure, "-n", "--json")) == ["a silence cuts a request (4 of 8 bytes)"]
    assert "    Reason: a silence cuts a request (4 of 8 bytes)" in live(tape, pure, "-n", "-V")


@ENGINES
def test_a_silence_cuts_a_request_after_an_unanswered_one(pure: bool, tmp_path: Path) -> None:
    tape = tmp_path / "unanswered.tape"
    cut = bytes.fromhex("01 10 0000")
    tape.write_bytes(tape_of([(POLL, 100.0), (cut, 101.0), (POLL, 102.0), (ANSWER, 102.01)], random.Random(2)))
    assert noise_reasons(live(tape, pure, "-n", "--json")) == ["a silence cuts a request (4 bytes of it)"]


@ENGINES
def test_a_silence_cuts_the_answer(pure: bool, tmp_path: Path) -> None:
    tape = tmp_path / "answer.tape"
    tape.write_bytes(tape_of([(POLL, 100.0), (ANSWER[:5], 100.01), (POLL, 101.0), (ANSWER, 101.01)],
                             random.Random(1)))
    out = live(tape, pure, "-n", "--json")
    assert noise_reasons(out) == ["a silence cuts the response (5 of 9 bytes)"]
    # (the request is not answered: the capture went on past its timeout, not ended inside its answer)
    first = json.loads(out[0])
    assert (first["unanswered"], first["notes"]) == (True, [])


@ENGINES
def test_the_capture_ends_inside_a_request_still(pure: bool, tmp_path: Path) -> None:
    """A tape that ends right after the cut bytes (no silence long enough to close them first)."""
    reads = [(POLL, 1.0), (b"", 1.005), (ANSWER, 1.010), (b"", 1.015), (POLL[:4], 1.020), (b"", 1.022)]
    tape = tmp_path / "end.tape"
    tape.write_bytes(b"".join(_TAPE_EVENT.pack(1000 + at, T0 + int(at * 1e9), len(data)) + data
                              for data, at in reads))
    reasons = noise_reasons(live(tape, pure, "-n", "--json"))
    assert reasons == ["the capture ends inside a request (4 of 8 bytes)"]


@ENGINES
def test_a_file_with_times_says_what_live_says(pure: bool, tmp_path: Path) -> None:
    # (the bytes before the silence are noise in a file as in live, and the silence cuts them: not the end)
    capture = tmp_path / "silence.pcap"
    write_pcap(capture, [(POLL, T0), (ANSWER, T0 + 10**7), (POLL[:4], T0 + 10**9), (POLL, T0 + 2 * 10**9),
                         (ANSWER, T0 + 2 * 10**9 + 10**7)])
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    run = subprocess.run([sys.executable, "-m", "dissector", "-n", "--json", str(capture)], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert noise_reasons(run.stdout.splitlines()) == ["a silence cuts a request (4 of 8 bytes)"]
