"""Bytes with a good CRC that the line bounds are a frame, whatever length the protocol table expects of their
layout (framing/bounded.py); before, they were noise, where tshark's mbrtu (a record, a frame) shows a frame:
pymodbus 3.16's answer to FC8 sub-function 15h (Get/Clear Modbus Plus Statistics: 118 bytes, where the table's
FC8 layout takes 8) was '118 bytes of noise at offset 8', and '11 80 01' + CRC (an exception to function 0) '5
bytes of noise'. A bound: a record's start or end, a silence, the end of a frame taken, an intact frame after,
the end of the input. A raw stream resynchronising inside noise guesses no length (1 in 65,536 per try).
Exact lines, the engine and VW3_PURE_PYTHON=1 alike (summary, -V, --json, -x); the plugin:
tests/integration/test_lua_bounded_runs.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import CHAR_NS, assert_same, write_pcap

T0 = 1_700_000_000 * 10**9
ASK_PLUS = rtu("01 08 0015 0003")  # pymodbus 3.16's GetClearModbusPlusRequest (operation 3: get statistics)
PLUS = rtu("01 08 0015 0003" + "00" * 110)  # its answer: the operation, then 55 statistics words
EXCEPTION_0, READ_COILS = rtu("11 80 01"), rtu("11 01 0013 0025")
POLL, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
ASKED = ("1 request   Diagnostics 15h unknown sub-function = 3 [warning: diagnostic sub-function 21 is not defined"
         " by the spec]  CRC ok")
LONG = ("1 response  Diagnostics 15h unknown sub-function data 00030000000000000000000000000000… (+96 bytes)"
        " [#{}]"
        " [warning: frame length 118 disagrees with the spec's layout (8 bytes), its CRC good]"
        " [warning: diagnostic sub-function 21 is not defined by the spec]  CRC ok")
FUNCTION_0 = ("17 exception Function 0: exception 1 (Illegal Function) [no request] [response without a matching"
              " request in the capture]  CRC ok")
READ = "1 request   Read Holding Registers 0..1 (2)"
UNANSWERED = "[the capture ends before any response: not known whether it was answered]  CRC ok"


def _lines(capture: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str]]:
    """The summary and -V lines, the engine's equal to the Python stages' (--json, -x too)."""
    out, _ = assert_same([str(capture)], monkeypatch)
    verbose, _ = assert_same([str(capture), "-V"], monkeypatch)
    for option in (["--json"], ["-x"]):
        assert_same([str(capture), option[0]], monkeypatch)
    return out.splitlines(), verbose.splitlines()


def test_a_record_with_a_good_crc_is_a_frame(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "plus.pcap"
    write_pcap(capture, [(ASK_PLUS, T0), (PLUS, T0 + 10**8)])
    out, verbose = _lines(capture, monkeypatch)
    assert out == [f"     1  0.000000000   {ASKED}", "     2  0.100000000   " + LONG.format("1, 100.0 ms")]
    assert "    Warning: frame length 118 disagrees with the spec's layout (8 bytes), its CRC good" in verbose
    write_pcap(capture, [(EXCEPTION_0, T0)])
    out, _ = _lines(capture, monkeypatch)
    assert out == [f"     1  0.000000000  {FUNCTION_0}"]


def test_raw_bytes_between_frames(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "between.bin"
    capture.write_bytes(POLL + ANSWER + ASK_PLUS + PLUS + POLL)
    out, _ = _lines(capture, monkeypatch)
    assert out[2:] == [f"     3            -   {ASKED}", "     4            -   " + LONG.format("3"),
                       f"     5            -   {READ} {UNANSWERED}"]
    capture.write_bytes(READ_COILS + EXCEPTION_0)  # (a frame's end, then the end of the input)
    out, _ = _lines(capture, monkeypatch)
    assert out == ["     1            -  17 request   Read Coils 19..55 (37) [no response]  CRC ok",
                   f"     2            -  {FUNCTION_0}"]


def test_no_length_is_guessed_where_nothing_bounds_the_start(tmp_path: Path,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "raw.bin"
    capture.write_bytes(EXCEPTION_0)  # (a raw file's first byte may be any frame's middle)
    out, _ = _lines(capture, monkeypatch)
    assert out[0] == "     1            -   - noise     5 bytes of noise at offset 0: 11 80 01 81 c5"
    capture.write_bytes(bytes.fromhex("AA BB") + EXCEPTION_0 + POLL)
    out, _ = _lines(capture, monkeypatch)
    assert out == ["     1            -   - noise     7 bytes of noise at offset 0: aa bb 11 80 01 81 c5",
                   f"     2            -   {READ} {UNANSWERED}"]


def test_a_run_crosses_no_read_end(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (USB reads cut the long answer anywhere: a record's end bounds a run, so none across it is one; the bytes
    # stay noise, as before, where a CRC tried at every read's end would invent frames on a noisy line)
    capture = tmp_path / "bursts.pcap"
    start = T0 + 10**7
    write_pcap(capture, [(ASK_PLUS, T0), (PLUS[:50], start), (PLUS[50:100], start + 50 * CHAR_NS),
                         (PLUS[100:], start + 100 * CHAR_NS), (POLL, T0 + 10**9)])
    out, _ = _lines(capture, monkeypatch)
    assert out[1] == ("     2  0.010000000   - noise     118 bytes of noise at offset 8: 01 08 00 15 00 03 00 00 00 00"
                      " 00 00 00 00 00 00…")


def test_hex_arguments_are_records(monkeypatch: pytest.MonkeyPatch) -> None:
    # (each --hex argument is a record: the engine's path keeps their ends, /work/patches/frames-hex-bounded-runs.diff)
    out, _ = assert_same(["--hex", EXCEPTION_0.hex(" ")], monkeypatch)
    assert out.splitlines() == [f"     1            -  {FUNCTION_0}"]
    # (a typo's mending asks for the table's shapes: 6 bytes typed are an FC3 request without its CRC, not a 6-byte
    # frame whose last two bytes are a bad CRC)
    out, _ = assert_same(["--hex", "01 03 0000 0002"], monkeypatch)
    assert out.splitlines() == [f"     1            -   {READ} [the capture ends before any response: not known whether"
                                " it was answered] [no CRC typed: append C4 0B (CRC 0x0BC4)]  CRC computed (none typed)"]
