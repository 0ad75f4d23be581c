"""A request or an answer a silence cuts, read from a timed file (pcap, pcapng, a hex dump with times): vw3-decode
says what live says, 'a silence cuts a request (4 of 8 bytes)' (tests/differential/test_silence_cut.py), where it
said 'no valid frame' (and 'the capture ends inside a request' for bytes a silence cut before the file's end): the
decode of a file weighs the bytes up to a silence as live closes them there (framing/bounded.py _silence_cut).
Exact lines (summary, -V, --json) of the engine and VW3_PURE_PYTHON=1; live on a tape of the same reads, with a
silence shorter than live's IDLE_FLUSH_LONG (live closes nothing then: the next read's silence cuts the bytes, as in
a file). A frame with a good CRC across a silence stays a frame. The plugin's:
tests/integration/test_lua_silence_cut.py."""
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
from test_silence_cut import live, noise_reasons
from test_timed_summary import write_pcap, write_pcapng

POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
T0 = 1_700_000_000 * 10**9
MS = 10**6
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def write_hex(path: Path, records: list[tuple[bytes, int]]) -> None:
    """A hex dump with a time on each line (sources/hexdump.py), one record a line."""
    path.write_text("".join(f"{ns // 10**9}.{ns % 10**9:09d}  {data.hex(' ').upper()}\n" for data, ns in records))


WRITERS = {"pcap": write_pcap, "pcapng": write_pcapng, "txt": write_hex}
FORMATS = pytest.mark.parametrize("form", sorted(WRITERS))


def column(form: str, seconds: float) -> str:
    """The time column at the form's precision: a nanosecond pcap's 9 decimals (as tshark shows them), 6."""
    return f"{seconds:12.9f}" if form == "pcap" else f"{seconds:12.6f}"


def decode(records: list[tuple[bytes, int]], form: str, pure: bool, tmp_path: Path, *options: str) -> list[str]:
    """vw3-decode's lines on a file of `records` (bytes, time in ns) in format `form`."""
    capture = tmp_path / f"capture.{form}"
    WRITERS[form](capture, records)
    return decode_file(capture, pure, *options)


def decode_file(capture: Path, pure: bool, *options: str) -> list[str]:
    """vw3-decode's lines on `capture`, by the compiled engine or (pure) the Python stages."""
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    run = subprocess.run([sys.executable, "-m", "dissector", "-n", *options, str(capture)], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stdout.splitlines()


NEXT_POLL = [(POLL, T0), (ANSWER, T0 + 10 * MS), (POLL[:4], T0 + 1000 * MS), (POLL, T0 + 2000 * MS),
             (ANSWER, T0 + 2010 * MS)]


@ENGINES
@FORMATS
def test_a_silence_cuts_the_next_poll(form: str, pure: bool, tmp_path: Path) -> None:
    assert decode(NEXT_POLL, form, pure, tmp_path)[2] == (
        f"     3 {column(form, 1.0)}   - noise     4 bytes of noise at offset 17: 01 03 00 00")
    assert noise_reasons(decode(NEXT_POLL, form, pure, tmp_path, "--json")) == [
        "a silence cuts a request (4 of 8 bytes)"]
    verbose = decode(NEXT_POLL, form, pure, tmp_path, "-V")
    at = verbose.index("Item 3: noise, 4 bytes at offset 17")
    assert verbose[at + 1].startswith("    Arrival time: ")  # (a noise item's time, as a frame's: hunt64)
    assert verbose[at : at + 1] + verbose[at + 2 : at + 4] == [
        "Item 3: noise, 4 bytes at offset 17", "    4 bytes of noise at offset 17: 01 03 00 00",
        "    Reason: a silence cuts a request (4 of 8 bytes)"]


@ENGINES
@FORMATS
def test_a_silence_cuts_the_answer(form: str, pure: bool, tmp_path: Path) -> None:
    records = [(POLL, T0), (ANSWER[:5], T0 + 10 * MS), (POLL, T0 + 1000 * MS), (ANSWER, T0 + 1010 * MS)]
    out = decode(records, form, pure, tmp_path, "--json")
    assert noise_reasons(out) == ["a silence cuts the response (5 of 9 bytes)"]
    # (the capture went on: the request is not answered, and no answer was cut by its end)
    first = json.loads(out[0])
    assert (first["unanswered"], first["notes"]) == (True, [])


@ENGINES
def test_a_silence_cuts_a_request_after_an_unanswered_one(pure: bool, tmp_path: Path) -> None:
    records = [(POLL, T0), (bytes.fromhex("01 10 0000"), T0 + 1000 * MS), (POLL, T0 + 2000 * MS),
               (ANSWER, T0 + 2010 * MS)]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == [
        "a silence cuts a request (4 bytes of it)"]


@ENGINES
def test_a_silence_before_the_end_of_the_capture(pure: bool, tmp_path: Path) -> None:
    """Two bytes of a request, a silence, one byte, the end: the silence cuts the request (it said 'the capture
    ends inside a request (3 of 8 bytes)' for both pieces), the byte after it is too short for a frame."""
    records = [(POLL, T0), (ANSWER, T0 + 10 * MS), (POLL[:2], T0 + 1000 * MS), (b"\x01", T0 + 2000 * MS)]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == [
        "a silence cuts a request (2 of 8 bytes)", "too short for a frame"]


@ENGINES
def test_a_frame_across_a_silence_stays_a_frame(pure: bool, tmp_path: Path) -> None:
    """Its CRC says the bytes after the silence are its own: a frame with a warning, no cut (timing.py)."""
    records = [(POLL[:4], T0), (POLL[4:], T0 + 1000 * MS), (ANSWER, T0 + 1500 * MS)]
    out = [json.loads(line) for line in decode(records, "pcap", pure, tmp_path, "--json")]
    assert [(item["kind"], item["crc_ok"]) for item in out] == [("request", True), ("response", True)]
    assert out[0]["warnings"] == [
        "silence of 997.708 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)"]


@ENGINES
def test_live_and_the_file_say_the_same(pure: bool, tmp_path: Path) -> None:
    """A silence of 100 ms, shorter than live's IDLE_FLUSH_LONG: live closes nothing at it, and the next read's
    silence cuts the bytes as in the file of those reads (both said 'no valid frame')."""
    reads = [(POLL, 100.0), (ANSWER, 100.01), (POLL[:4], 100.5), (POLL, 100.6), (ANSWER, 100.61)]
    tape = tmp_path / "short.tape"
    tape.write_bytes(tape_of(reads, random.Random(1)))
    said = ["a silence cuts a request (4 of 8 bytes)"]
    assert noise_reasons(live(tape, pure, "-n", "--json")) == said
    assert "    Reason: a silence cuts a request (4 of 8 bytes)" in live(tape, pure, "-n", "-V")
    records = [(data, T0 + round((at - 100.0) * 1000) * MS) for data, at in reads]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == said
