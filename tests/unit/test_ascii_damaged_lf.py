"""A Modbus ASCII line ended by CR and a byte other than LF (framing/ascii.py), found with a real peer
(pymodbus 3.16's ASCII server): the line ends at the CR and keeps the byte after it, so every byte is shown.
- after FC8 08/03 (Change ASCII Input Delimiter) the echo already ends with CR and the new character, which
  ends lines from then on (spec 6.8.1: it replaces LF "for future messages"): no warning (before: the echo was
  noise, "ASCII frame cut short by the next ':'", so the change was never learned, the request showed 'the
  capture ends before any response' and every later line was noise);
- any other byte in the LF's place (a damaged LF), before the next ':' or the end of the capture: a frame with
  a warning naming the byte, damaged too when its LRC is bad (before: noise, and its request unanswered).
Exact summary lines, under the engine and VW3_PURE_PYTHON=1 (ASCII is framed in Python either way), whatever
the chunks; the plugin: tests/integration/test_lua_ascii_damaged_lf.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import ascii_items, run_cli, use_engine

from dissector.framing.ascii import AsciiFramer
from dissector.model import Chunk

CHANGE = b":110800032100C3"  # slave 17, 08/03: '!' (21h) in place of LF
REQUEST, ANSWER = b":110300000001EB", b":1103020005E5"  # Read Holding Registers 0 of slave 17, its answer 5
DAMAGED = "line ends with CR then {:02X}h where LF belongs (the spec ends a frame with CR LF)"
# (a request to a slave that set '!': before, DAMAGED, "where LF belongs", though LF was no longer its delimiter)
NOT_SET = "line ends with CR then {:02X}h where slave 17's delimiter 21h belongs (set by its answer to 08/03)"
SET = "Diagnostics 03h Change ASCII Input Delimiter = 8448"
READ = "Read Holding Registers 0"

# (bytes, summary lines)
CASES = {
    "08/03 echo ending with the new character": (
        CHANGE + b"\r\n" + CHANGE + b"\r!" + REQUEST + b"\r!" + ANSWER + b"\r!",
        [f"     1            -  17 request   {SET} [new ASCII input delimiter: '!' (21h)]  LRC ok",
         f"     2            -  17 response  {SET} [#1]  LRC ok",
         f"     3            -  17 request   {READ}  LRC ok",
         f"     4            -  17 response  {READ}: 0=5 [#3]  LRC ok"],
    ),
    "a damaged LF": (
        REQUEST + b"\r\n" + ANSWER + b"\r\x0b" + REQUEST + b"\r\n" + ANSWER + b"\r\n",
        [f"     1            -  17 request   {READ}  LRC ok",
         f"     2            -  17 response  {READ}: 0=5 [#1] [warning: {DAMAGED.format(0x0B)}]  LRC ok",
         f"     3            -  17 request   {READ}  LRC ok",
         f"     4            -  17 response  {READ}: 0=5 [#3]  LRC ok"],
    ),
    "a damaged LF at the end of the capture": (
        REQUEST + b"\r\n" + ANSWER + b"\r\x0b",
        [f"     1            -  17 request   {READ}  LRC ok",
         f"     2            -  17 response  {READ}: 0=5 [#1] [warning: {DAMAGED.format(0x0B)}]  LRC ok"],
    ),
    "a damaged LF and a bad LRC": (  # (a damaged frame, as one ended by CR LF with a bad LRC is)
        REQUEST + b"\r\n:110302000500\r\x0b" + REQUEST + b"\r\n" + ANSWER + b"\r\n",
        [f"     1            -  17 request   {READ}  LRC ok",
         f"     2            -  17 response  {READ}: 0=5 [#1] [warning: {DAMAGED.format(0x0B)}]  "
         "LRC BAD (received 0x00, expected 0xE5)",
         f"     3            -  17 request   {READ}  LRC ok",
         f"     4            -  17 response  {READ}: 0=5 [#3]  LRC ok"],
    ),
    "another delimiter than the one 08/03 set": (  # ('#' after the echo set '!': '!' belongs, and ends lines)
        CHANGE + b"\r\n" + CHANGE + b"\r!" + REQUEST + b"\r#" + ANSWER + b"\r!",
        [f"     1            -  17 request   {SET} [new ASCII input delimiter: '!' (21h)]  LRC ok",
         f"     2            -  17 response  {SET} [#1]  LRC ok",
         f"     3            -  17 request   {READ} [warning: {NOT_SET.format(0x23)}]  LRC ok",
         f"     4            -  17 response  {READ}: 0=5 [#3]  LRC ok"],
    ),
}


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("case", list(CASES))
def test_summary_and_every_byte(case: str, pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    data, lines = CASES[case]
    path = tmp_path / "capture.txt"
    path.write_bytes(data)
    assert run_cli(["--mode", "ascii", str(path)]) == (0, "\n".join(lines) + "\n", "")
    # (the frames' bytes, the byte in the LF's place with them, are the capture's)
    items = [json.loads(row) for row in run_cli(["--mode", "ascii", "--json", str(path)])[1].splitlines()]
    assert b"".join(bytes.fromhex(item["raw"]) for item in items) == data


def test_the_hex_dump_shows_the_byte_in_the_lf_s_place(tmp_path: Path) -> None:
    path = tmp_path / "capture.txt"
    path.write_bytes(CASES["a damaged LF at the end of the capture"][0])
    dump = run_cli(["--mode", "ascii", "-x", str(path)])[1].split("\n\n")[1]
    assert dump.splitlines()[1] == "0000  3a 31 31 30 33 30 32 30 30 30 35 45 35 0d 0b      :1103020005E5.."


@pytest.mark.parametrize("case", list(CASES))
def test_the_same_whatever_the_chunks(case: str) -> None:
    data = CASES[case][0]
    whole = ascii_items(data)
    for size in (1, 2, 3, 16):
        assert ascii_items(data, size) == whole


def test_a_line_cut_in_its_digits_stays_noise() -> None:
    # (CR and a byte after too few hex pairs: no frame, its bytes one noise item)
    framer = AsciiFramer()
    out = framer.feed(Chunk(b":1103\r\x0b" + REQUEST + b"\r\n")) + framer.finish()
    assert [(type(item).__name__, item.raw) for item in out] == [("Noise", b":1103\r\x0b"),
                                                                 ("Frame", REQUEST + b"\r\n")]
