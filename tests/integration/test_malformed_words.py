"""Data that end before their layout does are malformed, said in the same words by vw3-decode (compiled engine
and VW3_PURE_PYTHON=1) and the plugin: the words protocol/grammar.py shortfall derives from the layout's
description (data/modbus.toml [layouts]), which codegen/decode_lua.py's readers say too.
- A byte count past the end of the data (FC16, FC23 with an odd count of 3 and 2 data bytes; FC20's count of 7
  with 3 bytes): vw3-decode decoded them as valid (`Write Multiple Registers 0: 0=1`, `Odd byte: (empty)`,
  `Read File Record 0 record group(s)`): Construct's compiled parsers read what was there of a count. The
  plugin said malformed, as the spec's byte count definitions have it (the data the count gives are not
  there).
- Truncated fixed fields: vw3-decode showed Construct's error text (`stream read less than specified amount,
  expected 2, found 1 at (parsing) -> quantity`), the plugin `too short for start and quantity`."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
T0 = 1700000000.0

NO_ANSWER = "[the capture ends before any response: not known whether it was answered]"
# (hex without its CRC; the summary line from its time on; the -V lines of the frame's tree; warnings before)
PAST_THE_END = [
    ("0C 10 0000 0001 03 0001", "0.000000  12 request   Write Multiple Registers (malformed)",
     ["Slave: 12", "Function: 16 (0x10) Write Multiple Registers", "CRC: 0xC06E [CRC ok]"], []),
    ("01 17 0000 0001 0000 0001 03 000D", "0.000000   1 request   Read/Write Multiple Registers (malformed)",
     ["Slave: 1", "Function: 23 (0x17) Read/Write Multiple Registers", "CRC: 0xABC4 [CRC ok]"], []),
    ("01 14 07 06 0004", "0.000000   1 request   Read File Record (malformed)",
     ["Slave: 1", "Function: 20 (0x14) Read File Record", "CRC: 0x7FD1 [CRC ok]"],
     ["frame length 8 disagrees with the spec's layout (12 bytes), its CRC good"]),
]
PAST = "malformed request: byte_count past the end"


def decode_frames(frames: list[bytes], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                  *options: str) -> str:
    """vw3-decode's output of `frames`, a pcap record each, half a second apart (the plugin's capture too)."""
    use_engine(monkeypatch, pure)
    capture = write_pcap(tmp_path / "frames.pcap", [(frame, T0 + index * 0.5) for index, frame in enumerate(frames)])
    status, out, err = run_cli([str(capture), *options])
    assert status == 0, err
    return out


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("case", PAST_THE_END, ids=["fc16", "fc23", "fc20"])
def test_a_byte_count_past_the_end_is_malformed(case: tuple, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                pure: bool) -> None:
    data, line, tree, before = case
    frame = rtu(data)
    warnings = [*before, PAST]
    tail = "".join(f" [warning: {text}]" for text in warnings)
    out = decode_frames([frame], tmp_path, monkeypatch, pure, "-n")
    assert out.splitlines() == [f"     1     {line} {NO_ANSWER}{tail}  CRC ok"]
    out = decode_frames([frame], tmp_path, monkeypatch, pure, "-n", "-V")
    assert out.splitlines()[3:] == [
        *(f"        {text}" for text in tree), f"    Note: {NO_ANSWER[1:-1]}", *(f"    Warning: {text}" for text in warnings),
        "",
    ]
    out = decode_frames([frame], tmp_path, monkeypatch, pure, "-n", "-T", "fields", "-e", "warnings")
    assert out == ",".join(warnings) + "\n"


# Fixed fields the data end inside: the layout's fixed head named whole (grammar.fixed_head), as the plugin does.
TRUNCATED = [
    ("01 03 0000 00", "too short for start and quantity"),
    ("01 05 0001 FF", "too short for address and value"),
    ("01 06 0001 00", "too short for address and value"),
    ("01 0F 0000 00", "too short for start, quantity and byte_count"),
    ("01 10 0000 00", "too short for start, quantity and byte_count"),
    ("01 14", "too short for byte_count"),
    ("01 16 0001 00FF", "too short for address, and_mask and or_mask"),
    ("01 2B 0E", "too short for read_code and object_id"),
]


def _frames() -> list[bytes]:
    return [rtu(case[0]) for case in PAST_THE_END] + [rtu(data) for data, _ in TRUNCATED]


def _warnings() -> list[str]:
    layout = [f"frame length {len(rtu(data))} disagrees with the spec's layout ({size} bytes), its CRC good"
              for (data, _), size in zip(TRUNCATED, [8, 8, 8, 221, 9, 5, 10, 7])]
    return [PAST, PAST, f"{PAST_THE_END[2][3][0]},{PAST}",
            *(f"{text},malformed request: {words}" for text, (_, words) in zip(layout, TRUNCATED))]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_words(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(_frames(), tmp_path, monkeypatch, pure, "-n", "-T", "fields", "-e", "warnings")
    assert out.splitlines() == _warnings()


def test_the_plugin_says_the_same(tmp_path: Path) -> None:
    capture = write_pcap(tmp_path / "malformed.pcap",
                         [(frame, T0 + index * 0.5) for index, frame in enumerate(_frames())])
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-E", "aggregator=,", "-e", "vw3.warning",
                     "-e", "_ws.col.Info")
    assert not lua_errors(got.stdout + got.stderr)
    names = ["12 Write Multiple Registers", "1 Read/Write Multiple Registers", "1 Read File Record",
             "1 Read Holding Registers", "1 Write Single Coil", "1 Write Single Register", "1 Write Multiple Coils",
             "1 Write Multiple Registers", "1 Read File Record", "1 Mask Write Register",
             "1 Encapsulated Interface Transport"]
    assert got.stdout.splitlines() == [f"{warnings}|{name} request (malformed)"
                                       for warnings, name in zip(_warnings(), names)]


# An exception with a byte after its code: vw3-decode warned it (the exception layout's trailing), the plugin
# did not (it read the code and stopped). Now both warn.
EXCEPTION_TAIL = [rtu("01 03 0000 0001"), rtu("01 83 02 00")]
TAIL_WARNINGS = ["frame length 6 disagrees with the spec's layout (5 bytes), its CRC good",
                 "unexpected bytes after the data (1)"]


@pytest.mark.parametrize("pure", [False, True])
def test_an_exception_with_bytes_after_its_code(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(EXCEPTION_TAIL, tmp_path, monkeypatch, pure, "-n")
    assert out.splitlines()[1] == (
        "     2     0.500000   1 exception Read Holding Registers: exception 2 (Illegal Data Address) [#1, 500.0 ms]"
        + "".join(f" [warning: {text}]" for text in TAIL_WARNINGS) + "  CRC ok")


def test_the_plugin_warns_an_exceptions_bytes_after_its_code(tmp_path: Path) -> None:
    capture = write_pcap(tmp_path / "exception.pcap",
                         [(frame, T0 + index * 0.5) for index, frame in enumerate(EXCEPTION_TAIL)])
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-E", "aggregator=,", "-e", "_ws.col.Info",
                     "-e", "vw3.warning", "-e", "vw3.exception_code", "-e", "vw3.request_frame")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [
        "1 Read Holding Registers request 0|||",
        f"1 Read Holding Registers exception 2 (Illegal Data Address)|{','.join(TAIL_WARNINGS)}|2|1",
    ]


# An exception with no code (01 83 + CRC): vw3-decode said malformed; the plugin read the CRC's first byte as its
# code ('exception code 65 is not defined by the spec'). Now both say malformed and show the code as `?`.
NO_CODE = [rtu("01 03 0000 0001"), rtu("01 83")]
NO_CODE_WARNINGS = ["frame length 4 disagrees with the spec's layout (5 bytes), its CRC good",
                    "malformed exception: too short for exception_code"]


@pytest.mark.parametrize("pure", [False, True])
def test_an_exception_without_a_code(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(NO_CODE, tmp_path, monkeypatch, pure, "-n")
    assert out.splitlines()[1] == (
        "     2     0.500000   1 exception Read Holding Registers: exception ? (Missing exception code) [#1, 500.0 ms]"
        + "".join(f" [warning: {text}]" for text in NO_CODE_WARNINGS) + "  CRC ok")
    out = decode_frames(NO_CODE, tmp_path, monkeypatch, pure, "-n", "-V")
    assert "        Exception code: Missing exception code (?)" in out.splitlines()


def test_the_plugin_says_an_exception_without_a_code_is_malformed(tmp_path: Path) -> None:
    capture = write_pcap(tmp_path / "exception.pcap", [(frame, T0 + index * 0.5) for index, frame in enumerate(NO_CODE)])
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-E", "aggregator=,", "-e", "_ws.col.Info",
                     "-e", "vw3.warning", "-e", "vw3.exception_code", "-e", "vw3.request_frame")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [
        "1 Read Holding Registers request 0|||",
        f"1 Read Holding Registers exception ? (Missing exception code)|{','.join(NO_CODE_WARNINGS)}||1",
    ]
