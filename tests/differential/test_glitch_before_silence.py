"""A run of 1 to 3 glitch bytes before a silence, read from a timed file (pcap, pcapng, a hex dump with times): live
closes them at the silence, too few for a frame, 'too short for a frame' (framing/rtu.py _run, n - i < MIN_ADU at
finish); the file of the same reads said 'no valid frame' for them (the bytes after the silence, the next poll,
were in its buffer). Now the file says what live says (framing/bounded.py _no_frame, _add_skipped), as for a request
a silence cuts (test_silence_cut_files.py). Exact lines (summary, -V, --json reasons) of the engine and
VW3_PURE_PYTHON=1; live on tapes of the same reads, a long silence (live closes the bytes) and one shorter than
IDLE_FLUSH_LONG (live closes nothing: the file's rule decides); four bytes or more stay 'no valid frame' as live's.
The plugin's: tests/integration/test_lua_glitch_before_silence.py."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import rtu
from live_tape import tape_of
from test_silence_cut import live, noise_reasons
from test_silence_cut_files import ENGINES, FORMATS, column, decode

POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
T0 = 1_700_000_000 * 10**9
MS = 10**6
GLITCHES = pytest.mark.parametrize("glitch", ["ff", "00", "ffff", "fe0080"])


def answered_then(glitch: bytes, after_ms: int = 500) -> list[tuple[bytes, int]]:
    """An answered poll, `glitch` after_ms later, the next answered poll a second after the first."""
    return [(POLL, T0), (ANSWER, T0 + 10 * MS), (glitch, T0 + after_ms * MS), (POLL, T0 + 1000 * MS),
            (ANSWER, T0 + 1010 * MS)]


@ENGINES
@FORMATS
@GLITCHES
def test_a_glitch_run_before_a_silence(glitch: str, form: str, pure: bool, tmp_path: Path) -> None:
    records = answered_then(bytes.fromhex(glitch))
    assert noise_reasons(decode(records, form, pure, tmp_path, "--json")) == ["too short for a frame"]
    size = len(glitch) // 2
    shown = f"{size} byte{'s' if size > 1 else ''} of noise at offset 17: {bytes.fromhex(glitch).hex(' ')}"
    assert decode(records, form, pure, tmp_path)[2] == f"     3 {column(form, 0.5)}   - noise     {shown}"
    verbose = decode(records, form, pure, tmp_path, "-V")
    at = verbose.index(f"Item 3: noise, {size} byte{'s' if size > 1 else ''} at offset 17")
    assert verbose[at + 1].startswith("    Arrival time: ")  # (a noise item's time, as a frame's: hunt64)
    assert verbose[at + 2 : at + 4] == [f"    {shown}", "    Reason: too short for a frame"]


@ENGINES
def test_glitch_bytes_after_a_frame_in_its_record(pure: bool, tmp_path: Path) -> None:
    """A bus driver's turn-around after the answer, in the answer's record: the silence after them closes them."""
    records = [(POLL, T0), (ANSWER + b"\xff\xff", T0 + 10 * MS), (POLL, T0 + 1000 * MS), (ANSWER, T0 + 1010 * MS)]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == ["too short for a frame"]


@ENGINES
def test_each_stretch_between_silences(pure: bool, tmp_path: Path) -> None:
    """Bytes no frame starts at across silences (one skip, _add_skipped): each stretch its own reason."""
    records = [(POLL, T0), (ANSWER, T0 + 10 * MS), (bytes.fromhex("fefe"), T0 + 300 * MS),
               (bytes.fromhex("fefefefe"), T0 + 500 * MS), (b"\xfe", T0 + 700 * MS), (POLL, T0 + 1000 * MS),
               (ANSWER, T0 + 1010 * MS)]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == [
        "too short for a frame", "no valid frame", "too short for a frame"]


@ENGINES
def test_at_the_start_and_before_an_unanswered_poll(pure: bool, tmp_path: Path) -> None:
    records = [(b"\xff", T0), (POLL, T0 + 500 * MS), (b"\x00", T0 + 600 * MS), (POLL, T0 + 1600 * MS),
               (ANSWER, T0 + 1610 * MS)]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == [
        "too short for a frame", "too short for a frame"]


@ENGINES
def test_four_bytes_are_no_valid_frame_still(pure: bool, tmp_path: Path) -> None:
    """Enough bytes for a frame's minimum: live weighs them (no frame at their first byte), as the file does."""
    records = answered_then(bytes.fromhex("11223344"))
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == ["no valid frame"]


@ENGINES
@pytest.mark.parametrize("after", [0.5, 0.9], ids=["long", "short"])
def test_live_and_the_file_say_the_same(after: float, pure: bool, tmp_path: Path) -> None:
    """A silence of 490 ms after the glitch (live closes it there) or of 90 ms (live closes nothing: the next read's
    silence decides, as in the file)."""
    reads = [(POLL, 100.0), (ANSWER, 100.01), (b"\xff\xff", 100.0 + after), (POLL, 101.0), (ANSWER, 101.01)]
    tape = tmp_path / "glitch.tape"
    tape.write_bytes(tape_of(reads, random.Random(1)))
    said = ["too short for a frame"]
    assert noise_reasons(live(tape, pure, "-n", "--json")) == said
    assert "    Reason: too short for a frame" in live(tape, pure, "-n", "-V")
    records = [(data, T0 + round((at - 100.0) * 1000) * MS) for data, at in reads]
    assert noise_reasons(decode(records, "pcap", pure, tmp_path, "--json")) == said
