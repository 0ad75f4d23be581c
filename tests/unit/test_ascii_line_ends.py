"""Modbus ASCII line ends and the end of the capture (framing/ascii.py), as a Wireshark user expects them:
- a line whose LF was lost (CR, then the next ':') is a frame with a warning, as one that lost its CR is
  (before: noise, "ASCII frame cut short by the next ':'", and its answer 'response [no request]'); a line cut
  in its digits by the next ':' stays noise;
- the answer awaited cut by the end of the capture says so as RTU does, on the request and as the noise's
  reason, its size in bytes on the wire ("the capture ends inside the response (15 of 23 bytes)"; before:
  "ASCII frame cut off by the end of the capture" and "the capture ends before any response").
Exact outputs for exact bytes, under the engine and VW3_PURE_PYTHON=1; the plugin: tests/integration/
test_lua_ascii_line_ends.py."""
from __future__ import annotations

import io
import json
import re

import pytest

from dissector.app.cli import Environment, run
from dissector.framing.ascii import AsciiFramer
from dissector.model import Chunk, Frame
from dissector.pipeline import Dissector
from helpers import use_engine


def line(hex_text: str, check: int | None = None, end: bytes = b"\r\n") -> bytes:
    body = bytes.fromhex(hex_text)
    check = -sum(body) & 0xFF if check is None else check
    return b":" + (body + bytes([check])).hex().upper().encode() + end


REQUEST = line("0C 03 20 D0 00 03")  # :0C0320D00003FE CR LF, Read Holding Registers 8400..8402
ANSWER = line("0C 03 06 80 00 00 03 00 02")  # :0C030680000003000266 CR LF, 23 bytes
LOST_LF = "line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)"
LOST_LF_AT_END = "line ends with CR without LF, at the end of the capture (the spec ends a frame with CR LF)"
READ = "Read Holding Registers 8400..8402 (3)"
VALUES = "8400=32768 8401=3 8402=2"

# (bytes, summary lines)
CASES = {
    "lost LF": (
        line("0C 03 20 D0 00 03", end=b"\r") + ANSWER,
        [f"1 - 12 request {READ} [warning: {LOST_LF}] LRC ok",
         f"2 - 12 response {READ}: {VALUES} [#1] LRC ok"],
    ),
    "lost LF, bad LRC": (  # (damaged, as a line ended by LF with a bad LRC is)
        line("0C 03 20 D0 00 03", check=0, end=b"\r") + ANSWER,
        [f"1 - 12 request {READ} [warning: {LOST_LF}] LRC BAD (received 0x00, expected 0xFE)",
         "2 - 12 response Read Holding Registers (3): ?+0=32768 ?+1=3 ?+2=2 [#1] [addresses unknown: the "
         "request's LRC is bad] LRC ok"],  # (its request failed its check: decode/pairing.py trusted_request)
    ),
    "cut by the next colon": (  # (a hex digit before the ':': the line was cut, not ended)
        b":0C0320D0" + REQUEST + ANSWER,
        ["1 - - noise 9 bytes of noise at offset 0: 3a 30 43 30 33 32 30 44 30",
         f"2 - 12 request {READ} LRC ok",
         f"3 - 12 response {READ}: {VALUES} [#2] LRC ok"],
    ),
    "cut response": (
        REQUEST + ANSWER[:15],
        [f"1 - 12 request {READ} [the capture ends inside the response (15 of 23 bytes)] LRC ok",
         "2 - - noise 15 bytes of noise at offset 17: 3a 30 43 30 33 30 36 38 30 30 30 30 30 30 33"],
    ),
    "cut before its LF": (  # (the line is whole to its CR: before, noise and "inside the response (22 of 23")
        REQUEST + ANSWER[:-1],
        [f"1 - 12 request {READ} LRC ok",
         f"2 - 12 response {READ}: {VALUES} [#1] [warning: {LOST_LF_AT_END}] LRC ok"],
    ),
    "cut before the byte count": (
        REQUEST + b":0C03",
        [f"1 - 12 request {READ} [the capture ends inside the response (5 bytes of it)] LRC ok",
         "2 - - noise 5 bytes of noise at offset 17: 3a 30 43 30 33"],
    ),
    "cut exception": (
        REQUEST + b":0C83",
        [f"1 - 12 request {READ} "
         "[the capture ends inside the exception response (5 of 11 bytes)] LRC ok",
         "2 - - noise 5 bytes of noise at offset 17: 3a 30 43 38 33"],
    ),
    "cut request": (  # (no answer awaited: the line is cut, nothing more is known)
        REQUEST + ANSWER + REQUEST[:9],
        [f"1 - 12 request {READ} LRC ok",
         f"2 - 12 response {READ}: {VALUES} [#1] LRC ok",
         "3 - - noise 9 bytes of noise at offset 40: 3a 30 43 30 33 32 30 44 30"],
    ),
    "cut answer of another slave": (
        REQUEST + line("0B 03 06 80 00 00 03 00 02")[:15],
        [f"1 - 12 request {READ} [the capture ends before any response: not known whether it was answered] LRC ok",
         "2 - - noise 15 bytes of noise at offset 17: 3a 30 42 30 33 30 36 38 30 30 30 30 30 30 33"],
    ),
}


def decode(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    out, err = io.StringIO(), io.StringIO()
    assert run([*options, "-n", "-"], Environment(io.BytesIO(data), out, err, False, False)) == 0
    assert err.getvalue() == ""
    return out.getvalue()


def both(data: bytes, options: list[str], monkeypatch: pytest.MonkeyPatch) -> str:
    engine, pure = decode(data, options, monkeypatch, False), decode(data, options, monkeypatch, True)
    assert engine == pure
    return engine


def squeezed(text: str) -> list[str]:
    return [re.sub(r"\s+", " ", row.strip()) for row in text.splitlines()]


@pytest.mark.parametrize("case", CASES)
def test_summary(case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    data, expected = CASES[case]
    assert squeezed(both(data, [], monkeypatch)) == expected


@pytest.mark.parametrize("case", CASES)
def test_split_anywhere(case: str) -> None:
    # The answer does not depend on how the stream is split: fed a byte at a time, the same items.
    data = CASES[case][0]

    def items(splits: list[int]) -> list[tuple]:
        dissector = Dissector(framer=AsciiFramer())
        out = []
        cuts = [0, *splits, len(data)]
        for start, stop in zip(cuts, cuts[1:]):
            out += dissector.feed(Chunk(data[start:stop], None))
        out += dissector.finish()
        return [(item.offset, item.raw, item.warnings, item.notes) if isinstance(item, Frame)
                else (item.offset, item.raw, item.reason) for item in out]

    assert items(list(range(1, len(data)))) == items([])


def test_lost_lf_detail_and_json(monkeypatch: pytest.MonkeyPatch) -> None:
    data = CASES["lost LF"][0]
    tree = both(data, ["-V"], monkeypatch)
    assert tree.split("\n\n")[0].splitlines() == [
        "Frame 1: 16 bytes at offset 0, request (ASCII)",
        "    Modbus ASCII",
        "        Slave: 12",
        "        Function: 3 (0x03) Read Holding Registers",
        "        Start address: 8400 (0x20D0)",
        "        Quantity: 3 (0x3)",
        "        LRC: 0xFE [LRC ok]",
        "    Response in frame: 2",
        f"    Warning: {LOST_LF}",
    ]
    first, second = (json.loads(row) for row in both(data, ["--json"], monkeypatch).splitlines())
    assert (first["kind"], first["length"], first["raw"], first["response_frame"], first["warnings"]) == (
        "request", 16, "3a30433033323044303030303346450d", 2, [LOST_LF])
    assert (second["kind"], second["offset"], second["request_frame"], second["warnings"]) == (
        "response", 16, 1, [])


def test_cut_response_detail_and_json(monkeypatch: pytest.MonkeyPatch) -> None:
    data = CASES["cut response"][0]
    reason = "the capture ends inside the response (15 of 23 bytes)"
    tree = both(data, ["-V"], monkeypatch)
    assert tree.split("\n\n")[1].splitlines() == [
        "Item 2: noise, 15 bytes at offset 17",
        "    15 bytes of noise at offset 17: 3a 30 43 30 33 30 36 38 30 30 30 30 30 30 33",
        f"    Reason: {reason}",
    ]
    # (the slave did answer, the capture ends inside it: not "No response")
    assert tree.split("\n\n")[0].splitlines()[-2:] == ["        LRC: 0xFE [LRC ok]", f"    Note: {reason}"]
    request, noise = (json.loads(row) for row in both(data, ["--json"], monkeypatch).splitlines())
    assert (request["unanswered"], request["notes"]) == (False, [reason])
    assert (noise["kind"], noise["offset"], noise["length"], noise["reason"]) == ("noise", 17, 15, reason)
