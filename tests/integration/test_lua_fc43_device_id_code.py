"""The plugin warns about an FC43/14 request whose Read Device ID code is not one of the spec's 01..04, as
vw3-decode does (tests/unit/test_fc43_device_id_code.py; data/modbus.toml [limits] device_id_code). Before: no
warning. Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
WARNING = "read device id code 5 outside the spec's 1..4 (a server answers exception 03)"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.request_frame", "-e", "vw3.warning"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


@pytest.mark.parametrize("two_pass", [True, False])
def test_an_illegal_code_is_warned_about(tmp_path: Path, two_pass: bool) -> None:
    frames = [rtu("01 2B 0E 05 00"), rtu("01 AB 03"), rtu("01 2B 0E 01 00"),
              rtu("01 2B 0E 01 01 00 00 01 00 03 41 42 43"), rtu("01 2B 0E 05 00"), rtu("01 2B 0E 00 00")]
    pcap = write_pcap(tmp_path / "fc43.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        f"1;;{WARNING}", "3;1;", "1;;", "2;3;", f"1;;{WARNING}",
        "1;;read device id code 0 outside the spec's 1..4 (a server answers exception 03)",
    ]
    tree = tshark(pcap, "-V", "-Y", "frame.number == 1", two_pass=two_pass)
    assert f"        [Expert Info (Warning/Protocol): {WARNING}]\n" in tree
    assert "    Read code: Unknown (5)\n" in tree
