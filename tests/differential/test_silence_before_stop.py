"""A frame cut by a silence, then the stop (hunt66b): live and the decode of its own -w file say the same.

An RTU request, 3 bytes of its answer (07 03 06), a silence, Ctrl-C. Live closed the bytes after 250 ms of silence
(live_capture.IDLE_FLUSH_LONG) and said 'a silence cuts the response (3 of 11 bytes)'; the decode of its -w file
(which ends with a record of no byte at the stop) said 'the capture ends inside the response (3 of 11 bytes)', on
the noise and on the request. With a silence shorter than 250 ms before the stop, both said the capture's end cut
it, though the line had been silent far longer than t3.5, which is what a silence on an RTU line is everywhere
else (timing.silence_before: the next bytes after it would have been cut by it, in live and in a file).

One rule now (StreamFramer.finish_at): the line silent t3.5 from its last bytes to the stop cuts what the framer
holds; shorter, the capture's end does; never in ASCII, whose line ends at its LF. Live (the engine's live path and
VW3_PURE_PYTHON=1) --json equals the decode of its -w file (engine and Python stages), key for key. The plugin:
tests/integration/test_lua_silence_before_stop.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu
from test_silence_cut import live
from test_silence_cut_files import decode_file as decode
from test_timed_summary import write_pcap

from dissector.app.live_capture import _TAPE_EVENT
from dissector.protocol.crc import lrc

REQUEST = rtu("07 03 0000 0003")  # 07 03 00 00 00 03 05 AD: its answer is 11 bytes
CUT = bytes.fromhex("07 03 06")
T0 = 1_700_000_000 * 10**9
MS = 10**6
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
WITHIN = "the capture ends {} ms after the request, within the 1000 ms timeout: not known whether it was answered"


def tape(path: Path, reads: list[tuple[bytes, float]], stop: float) -> Path:
    """A tape of these reads (bytes, seconds: each stamped when its last byte came) and the port's idle reads
    every 10 ms after each up to `stop` (the capture stops at the last idle read less the adapter's 20 ms)."""
    events: list[tuple[bytes, float]] = []
    for index, (data, at) in enumerate(reads):
        events.append((data, at))
        until = reads[index + 1][1] if index + 1 < len(reads) else stop
        events += [(b"", at + k * 0.010) for k in range(1, 1000) if at + k * 0.010 < until - 1e-9]
    if stop > events[-1][1] + 1e-9:
        events.append((b"", stop))
    path.write_bytes(b"".join(_TAPE_EVENT.pack(1000 + at, T0 + round(at * 1e6) * 1000, len(data)) + data
                              for data, at in events))
    return path


def live_and_file(tmp_path: Path, pure: bool, reads: list[tuple[bytes, float]], stop: float,
                  *options: str) -> list[tuple[str, object]]:
    """Live --json on the tape, held equal key for key to the decode of its -w file by both paths; what it says
    of each item: (kind, its notes or reason)."""
    written = tmp_path / f"live{int(pure)}.pcap"
    said = live(tape(tmp_path / "cut.tape", reads, stop), pure, "-n", "--json", *options, "-w", str(written))
    out = [json.loads(line) for line in said]
    for path_pure in (False, True):
        assert [json.loads(line) for line in decode(written, path_pure, "--json", *options)] == out
    return [(item["kind"], item["reason"] if item["kind"] == "noise" else item["notes"]) for item in out]


@ENGINES
def test_a_silence_of_450_ms_then_the_stop(pure: bool, tmp_path: Path) -> None:
    """hunt66b's: live closed the bytes at 250 ms of silence; the -w file said the capture's end cut them."""
    assert live_and_file(tmp_path, pure, [(REQUEST, 0.0), (CUT, 0.050)], 0.520) == [
        ("request", [WITHIN.format("504.0")]), ("noise", "a silence cuts the response (3 of 11 bytes)")]


@ENGINES
def test_a_silence_of_100_ms_then_the_stop(pure: bool, tmp_path: Path) -> None:
    """Shorter than live's 250 ms, longer than t3.5 (2.005 ms at 19200 baud): a silence all the same (both said
    'the capture ends inside the response (3 of 11 bytes)')."""
    assert live_and_file(tmp_path, pure, [(REQUEST, 0.0), (CUT, 0.050)], 0.170) == [
        ("request", [WITHIN.format("154.0")]), ("noise", "a silence cuts the response (3 of 11 bytes)")]


@ENGINES
def test_a_silence_shorter_than_t35_then_the_stop(pure: bool, tmp_path: Path) -> None:
    """Stopped 1 ms after the last byte came (0.43 ms of silence after its character): the capture's end cuts."""
    cut = "the capture ends inside the response (3 of 11 bytes)"
    assert live_and_file(tmp_path, pure, [(REQUEST, 0.0), (CUT, 0.050)], 0.071) == [
        ("request", [cut]), ("noise", cut)]


def line(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


@ENGINES
def test_an_ascii_line_cut_then_a_silence_then_the_stop(pure: bool, tmp_path: Path) -> None:
    """No silence cuts an ASCII frame (its LF ends it, test_live_ascii_silence.py): the capture's end does."""
    cut = "the capture ends inside the response (7 of 15 bytes)"
    assert live_and_file(tmp_path, pure, [(line("010300000001"), 0.0), (b":010302", 0.050)], 0.520,
                         "--mode", "ascii") == [("request", [cut]), ("noise", cut)]


# The rule at its edge, in a file: t3.5 is 2.005 ms at 19200 baud; the 3 bytes take 1.719 ms from the record's
# time (its first byte's), so a stop 3.7 ms after it is 1.98 ms of silence, 3.8 ms 2.08 ms.
EDGE = [(3.7, "the capture ends inside the response (3 of 11 bytes)"),
        (3.8, "a silence cuts the response (3 of 11 bytes)")]


@ENGINES
@pytest.mark.parametrize(("after", "said"), EDGE)
def test_the_edge_of_t35_in_a_file(pure: bool, after: float, said: str, tmp_path: Path) -> None:
    capture = tmp_path / "edge.pcap"
    write_pcap(capture, [(REQUEST, T0), (CUT, T0 + 50 * MS), (b"", T0 + 50 * MS + round(after * MS))])
    out = [json.loads(text) for text in decode(capture, pure, "--json")]
    assert [item.get("reason") for item in out] == [None, said]
    cut_by_the_end = said.startswith("the capture ends")
    assert out[0]["notes"] == [said if cut_by_the_end else WITHIN.format(f"{50 + after:.1f}")]


@ENGINES
def test_a_slower_line_has_a_longer_t35(pure: bool, tmp_path: Path) -> None:
    """At 9600 baud (--baud: the line's speed) t3.5 is 4.010 ms, and the 3 bytes take 3.438 ms: 6 ms after the
    record is 2.56 ms of silence, no silence there; at 19200 baud it is one."""
    capture = tmp_path / "slow.pcap"
    write_pcap(capture, [(REQUEST, T0), (CUT, T0 + 50 * MS), (b"", T0 + 56 * MS)])
    reasons = {baud: [item.get("reason") for item in map(json.loads, decode(capture, pure, "--json", "--baud", baud))]
               for baud in ("9600", "19200")}
    assert reasons == {"9600": [None, "the capture ends inside the response (3 of 11 bytes)"],
                       "19200": [None, "a silence cuts the response (3 of 11 bytes)"]}


@ENGINES
def test_the_cut_after_a_silence_inside_then_the_stop(pure: bool, tmp_path: Path) -> None:
    """Two pieces of a request, each after a silence, then the stop: a silence cuts both (bounded.py's cut at the
    first silence left its flag down: 'the capture ends inside a request (3 of 8 bytes)' on the second)."""
    poll, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    capture = tmp_path / "two.pcap"
    write_pcap(capture, [(poll, T0), (answer, T0 + 10 * MS), (poll[:2], T0 + 1000 * MS), (poll[:3], T0 + 2000 * MS),
                         (b"", T0 + 2500 * MS)])
    assert [item.get("reason") for item in map(json.loads, decode(capture, pure, "--json"))] == [
        None, None, "a silence cuts a request (2 of 8 bytes)", "a silence cuts a request (3 of 8 bytes)"]
