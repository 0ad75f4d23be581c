"""The plugin follows FC8/03 (Change ASCII Input Delimiter) as vw3-decode does
(tests/unit/test_ascii_delimiter.py): after the slave's echo, a line ending CR '!' is a frame (before: noise,
"ASCII frame cut short by the next ':'"); after the change back to LF, a frame whose line end is damaged
(before: noise, which encoded the defect; its warning: tests/integration/test_lua_ascii_damaged_lf.py). Real tshark with
-X lua_script:lua/vw3.lua, -2 and one pass, the bytes in one record and a line a record."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_ascii_delimiter import LINES  # noqa: E402

pytestmark = pytest.mark.integration

T0 = 1767225600.0
FIELDS = ["-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "vw3.kind", "-e", "vw3.noise.reason",
          "-e", "_ws.col.Info"]
INFO = ["1 Read Holding Registers request 1", "1 Read Holding Registers response 1",
        "1 Diagnostics request 03h Change ASCII Input Delimiter = 8448",
        "1 Diagnostics response 03h Change ASCII Input Delimiter = 8448"] + [
        "1 Read Holding Registers request 1", "1 Read Holding Registers response 1"] * 2 + [
        "1 Diagnostics request 03h Change ASCII Input Delimiter = 2560",
        "1 Diagnostics response 03h Change ASCII Input Delimiter = 2560",
        "1 Read Holding Registers request 1", "1 Read Holding Registers response 1"]


def tshark(pcap: Path, two_pass: bool) -> list[str]:
    result = run_tshark(pcap, *FIELDS, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_line_a_record(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "lines.pcap", [(data, T0 + index * 0.01) for index, data in enumerate(LINES)])
    # (one pass: profile `auto` has not seen the whole capture, each frame is [provisional])
    shown = [f"{kind}||{info}{'' if two_pass else ' [provisional]'}" for kind, info in zip([1, 2] * 6, INFO)]
    # (one pass: a line ended by CR and a byte not known to end lines is known only at the next ':' or the end,
    # after tshark showed its record: the next record shows it, the last one's is known at the end only)
    assert tshark(pcap, two_pass) == (shown if two_pass else shown[:10] + [
        "||(17 bytes continue)", f"{shown[10]} from #11; (15 bytes continue)"])


def test_one_record(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", [(b"".join(LINES), T0)])
    kinds, reasons, info = tshark(pcap, True)[0].split("|")
    assert kinds == "1,2,1,2,1,2,1,2,1,2,1,2"
    assert reasons == ""
    assert info.split("; ") == list(INFO)  # (-2: read as a file, nothing provisional)
