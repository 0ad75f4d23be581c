"""FC7's exception status is one byte: vw3-decode -V and the plugin's tree both write it at that width,
`Status: 109 (0x6D)` and `Status: 5 (0x05)` (the plugin's vw3.status was FC11's and FC12's uint16 field:
`(0x006d)`), while FC11's and FC12's status word keeps its four digits. vw3.status stays one filter name
for both, two fields of one name as Wireshark allows (`vw3.status == 0x6d`, `-e vw3.status`). Hex case is
compared as tests/integration/test_lua_tree_window_lines.py compares it: vw3-decode writes upper case, the
plugin Wireshark's lower case. Real tshark."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
FRAMES = ["0C 07", "0C 07 6D", "0C 07", "0C 07 05", "01 0B", "01 0B 0000 0003", "01 0C", "01 0C 06 FFFF 0003 0005"]
EXPECTED = ["Status: 109 (0x6D)", "Status: 5 (0x05)", "Status: 0 (0x0000)", "Status: 65535 (0xFFFF)"]


def _status_lines(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if line.strip().startswith("Status:")]


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    records = [(rtu(frame), T0 + 0.010 * index) for index, frame in enumerate(FRAMES)]
    return write_pcap(tmp_path_factory.mktemp("status") / "status.pcap", records)


def _tshark(pcap: Path, *args: str) -> str:
    result = run_tshark(pcap, *args)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


def test_status_at_its_width_in_both(capture: Path) -> None:
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(capture)], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout
    assert _status_lines(python) == EXPECTED
    assert _status_lines(_tshark(capture, "-V")) == [line.lower().replace("status", "Status") for line in EXPECTED]


def test_one_filter_name_for_both_widths(capture: Path) -> None:
    frames = _tshark(capture, "-Y", "vw3.status == 0x6d || vw3.status == 0xffff", "-T", "fields", "-e",
                     "frame.number", "-e", "vw3.status")
    assert frames.splitlines() == ["2\t109", "8\t65535"]
