"""A Modbus ASCII line with a good LRC is a frame whatever length the protocol table expects of its layout: the
':' and the line end bound it, as a record or a silence bounds an RTU run with a good CRC (framing/bounded.py,
tests/differential/test_bounded_runs.py). Before, the RTU run was a frame and the same bytes sent in ASCII were
noise: pymodbus 3.16's ASCII answer to FC8 sub-function 15h (Get/Clear Modbus Plus Statistics, 116 bytes where
the table's FC8 layout takes 6) was '237 bytes of noise ... no Modbus layout fits function 8 (LRC ok)', in
vw3-decode and in the plugin, and so were a read request with a byte after its quantity and an answer too short
for its byte count. A line with a bad LRC whose layout fits nothing stays noise. Exact lines and fields:
vw3-decode (engine and VW3_PURE_PYTHON=1: summary, --json) and the plugin (tshark -2, every field as
vw3-decode says it)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_compare import assert_same_as_vw3_decode, tshark_fields
from lua_harness import write_pcap

pytestmark = pytest.mark.integration

# pymodbus 3.16.1 FramerAscii: GetClearModbusPlusRequest(message=3, dev_id=1) and its response (operation 3,
# then 55 statistics words, all 0), byte for byte.
ASK_PLUS = b":010800150003DF\r\n"
PLUS = b":010800150003" + b"00" * 110 + b"DF\r\n"
TRAILING = b":01030000000100FB\r\n"  # a read of 1 register at 0, then a byte 00 after its quantity
READ, SHORT = b":0C0320D00003FE\r\n", b":0C0320D001\r\n"  # the answer: 2 bytes, too short for its byte count
BAD = b":01030000000100FA\r\n"  # the line with a trailing byte, its LRC wrong: noise
LINES = [ASK_PLUS, PLUS, TRAILING, READ, SHORT, BAD]
UNDEFINED = "diagnostic sub-function 21 is not defined by the spec"
SUMMARY = [
    f"     1            -   1 request   Diagnostics 15h unknown sub-function = 3 [warning: {UNDEFINED}]  LRC ok",
    "     2            -   1 response  Diagnostics 15h unknown sub-function data 00030000000000000000000000000000…"
    f" (+96 bytes) [#1] [warning: {UNDEFINED}]  LRC ok",
    "     3            -   1 request   Read Holding Registers 0 [no response] [warning: unexpected bytes after the"
    " data (1)]  LRC ok",
    "     4            -  12 request   Read Holding Registers 8400..8402 (3)  LRC ok",
    "     5            -  12 response  Read Holding Registers (malformed) [#4] [warning: malformed response:"
    " byte_count past the end]  LRC ok",
    "     6            -   - noise     19 bytes of noise at offset 303: 3a 30 31 30 33 30 30 30 30 30 30 30 31 30"
    " 30 46…",
]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_line_with_a_good_lrc_is_a_frame(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "lines.txt"
    path.write_bytes(b"".join(LINES))
    assert run_cli([str(path)]) == (0, "\n".join(SUMMARY) + "\n", "")
    records = [json.loads(line) for line in run_cli(["--json", str(path)])[1].splitlines()]
    assert [(r["kind"], r.get("slave"), r.get("function"), r.get("crc_ok"), r["length"]) for r in records] == [
        ("request", 1, 8, True, 17), ("response", 1, 8, True, 237), ("request", 1, 3, True, 19),
        ("request", 12, 3, True, 17), ("response", 12, 3, True, 13), ("noise", None, None, None, 19)]
    assert records[1]["fields"]["subfunction"] == 21 and records[1]["fields"]["data"] == "0003" + "00" * 110
    assert records[5]["reason"] == "no Modbus layout fits function 3 (LRC FA, expected FB)"


def test_the_plugin_frames_the_lines_alike(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "lines.pcap", [(line, 1700000000.0 + 0.1 * n) for n, line in enumerate(LINES)])
    fields = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.slave", "-e", "vw3.function",
              "-e", "vw3.warning", "-e", "vw3.noise.reason"]
    assert tshark_fields(pcap, fields) == [
        f"1;1;8;{UNDEFINED};", f"2;1;8;{UNDEFINED};", "1;1;3;unexpected bytes after the data (1);",
        "1;12;3;;", "2;12;3;malformed response: byte_count past the end;",
        "4;;;;no Modbus layout fits function 3 (LRC FA, expected FB)"]
    assert_same_as_vw3_decode(pcap)


def test_an_exception_too_long_for_its_layout(tmp_path: Path) -> None:
    # (the exception to the read, with a byte after its code: its function's high bit makes it an exception)
    lines = [READ, b":0C8302016E\r\n"]
    path = tmp_path / "exception.txt"
    path.write_bytes(b"".join(lines))
    assert run_cli([str(path)]) == (0, (
        "     1            -  12 request   Read Holding Registers 8400..8402 (3)  LRC ok\n"
        "     2            -  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#1] [warning:"
        " unexpected bytes after the data (1)]  LRC ok\n"), "")
    pcap = write_pcap(tmp_path / "exception.pcap", [(line, 1700000000.0 + 0.1 * n) for n, line in enumerate(lines)])
    assert tshark_fields(pcap, ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.exception_code",
                                "-e", "vw3.warning"]) == ["1;;", "3;2;unexpected bytes after the data (1)"]
