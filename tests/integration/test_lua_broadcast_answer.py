"""The plugin warns about a response from slave 0 as vw3-decode does (tests/unit/test_broadcast_answer.py): no
server answers a broadcast, so after a broadcast of its function it answers nothing, warned about with the
broadcast named; elsewhere with the broadcast address named and the note that it matches no request. Before:
only that note. Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
WRITE, WRITTEN = rtu("00 10 2329 0001 02 000A"), rtu("00 10 2329 0001")
AFTER = "response from slave 0 after broadcast #1: no server answers a broadcast"
ADDRESS = "response from slave 0, the broadcast address: a server answers with its own address"
UNMATCHED = "response without a matching request in the capture"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.broadcast", "-e", "vw3.request_frame",
          "-e", "vw3.response_frame", "-e", "vw3.warning", "-e", "vw3.note"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_response_from_slave_0(tmp_path: Path, two_pass: bool) -> None:
    frames = [WRITE, WRITTEN, rtu("01 03 0000 0001"), rtu("01 03 02 0005"), WRITTEN,
              rtu("00 06 2329 000A"), rtu("00 06 2329 000A")]
    pcap = write_pcap(tmp_path / "broadcast.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;1;;;;",
        f"2;;;;{AFTER};",
        "1;;;4;;" if two_pass else "1;;;;;",
        "2;;3;;;",
        f"2;;;;{ADDRESS};{UNMATCHED}",
        "1;1;;;;",
        "1;1;;;;",  # (a broadcast's own bytes: a broadcast again)
    ]
    tree = tshark(pcap, "-V", "-Y", "frame.number == 2", two_pass=two_pass)
    assert f"        [Expert Info (Warning/Protocol): {AFTER}]\n" in tree


def test_an_exception_from_slave_0(tmp_path: Path) -> None:
    # (-2 only: in one pass a record that starts 00 90 02, read as a glitch 00 then slave 144's Read Discrete
    # Inputs answer of 0x9C bytes, waits for those bytes before it is framed, and the records until then are
    # shown empty; vw3-decode waits as well, and shows the same once it knows)
    frames = [WRITE, rtu("00 90 02"), rtu("01 03 0000 0001"), rtu("01 03 02 0005")]
    pcap = write_pcap(tmp_path / "exception.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])
    assert tshark(pcap, *FIELDS).splitlines() == ["1;1;;;;", f"3;;;;{AFTER};", "1;;;4;;", "2;;3;;;"]
