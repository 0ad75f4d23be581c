"""The plugin reads Modbus ASCII line ends and the end of the capture as vw3-decode does
(tests/unit/test_ascii_line_ends.py): a line whose LF was lost (CR, then the next ':') is a frame with a
warning (before: noise, "ASCII frame cut short by the next ':'"), and the answer awaited cut by the end of the
capture says so on its request and as the noise's reason, as in RTU (before: "ASCII frame cut off by the end of
the capture"). Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass, the bytes in one record and a
line a record."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
REQUEST = b":0C0320D00003FE\r\n"  # Read Holding Registers 8400..8402 of slave 12
ANSWER = b":0C030680000003000266\r\n"
LOST_LF = "line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)"
CUT = "the capture ends inside the response (15 of 23 bytes)"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.request_frame", "-e", "vw3.response_frame",
          "-e", "vw3.unanswered", "-e", "vw3.warning", "-e", "vw3.note", "-e", "vw3.noise.reason"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> list[str]:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_line_that_lost_its_lf_is_a_frame(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "lost-lf.pcap", [(REQUEST[:-1] + ANSWER, T0)])
    assert tshark(pcap, *FIELDS, two_pass=two_pass) == [f"1,2;1;1;;{LOST_LF};;"]
    lines = [(REQUEST[:-1], T0), (ANSWER, T0 + 0.010)]
    pcap = write_pcap(tmp_path / "lost-lf-lines.pcap", lines)
    # (one pass: the line is known to end only at the next ':', in record 2, which shows it beside the answer,
    # the two linked to that record: an item settled by a later record is shown by it, lua/README.md)
    assert tshark(pcap, *FIELDS, two_pass=two_pass) == [
        f"1;;2;;{LOST_LF};;" if two_pass else ";;;;;;",
        "2;1;;;;;" if two_pass else f"1,2;2;2;;{LOST_LF};;",
    ]


def test_a_line_cut_by_the_next_colon_stays_noise(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "cut-colon.pcap", [(b":0C0320D0" + REQUEST, T0), (ANSWER, T0 + 0.010)])
    assert tshark(pcap, *FIELDS) == ["4,1;;2;;;;ASCII frame cut short by the next ':'", "2;1;;;;;"]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_answer_cut_by_the_end_of_the_capture(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "cut.pcap", [(REQUEST, T0), (ANSWER[:15], T0 + 0.010)])
    # (one pass: the end of the capture is known only after tshark has shown the last record, as in RTU)
    assert tshark(pcap, *FIELDS, two_pass=two_pass) == [
        f"1;;;;;{CUT};" if two_pass else "1;;;;;;",  # (answered, cut: not counted unanswered, 3a3a593)
        f"4;;;;;;{CUT}" if two_pass else ";;;;;;",
    ]
    exception = write_pcap(tmp_path / "cut-exception.pcap", [(REQUEST + b":0C83", T0)])
    cut = "the capture ends inside the exception response (5 of 11 bytes)"
    assert tshark(exception, *FIELDS, two_pass=two_pass) == [f"1,4;;;;;{cut};{cut}" if two_pass else "1;;;;;;"]


def test_a_cut_request_is_a_cut_line(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "cut-request.pcap", [(REQUEST + ANSWER + REQUEST[:9], T0)])
    assert tshark(pcap, *FIELDS) == ["1,2,4;1;1;;;;ASCII frame cut off by the end of the capture"]
