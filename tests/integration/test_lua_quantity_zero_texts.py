"""The plugin's Info column says an FC23 request's two windows as vw3-decode's summary does where it writes
none: `read 0, write 5 (0)` (vw3-decode's side: tests/unit/test_quantity_zero_texts.py), never its read
window alone (`0`); FC16's and FC15's and FC3's of none as before, `5 (0)`. Real tshark with
-X lua_script:lua/vw3.lua, -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    ("01 17 0000 0001 0005 0000 00", "Read/Write Multiple Registers", "read 0, write 5 (0)"),
    ("01 17 0000 0000 0005 0000 00", "Read/Write Multiple Registers", "read 0 (0), write 5 (0)"),
    ("01 17 0003 0002 0010 0000 00", "Read/Write Multiple Registers", "read 3..4 (2), write 16 (0)"),
    ("01 10 0005 0000 00", "Write Multiple Registers", "5 (0)"),
    ("01 0F 0005 0000 00", "Write Multiple Coils", "5 (0)"),
    ("01 03 0005 0000", "Read Holding Registers", "5 (0)"),
]


def test_info_column_as_vw3_decode(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "zero.pcap", [(rtu(frame), 1000.0 + 10 * k) for k, (frame, _, _) in enumerate(FRAMES)])
    result = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == [f"1 {name} request {info}" for _, name, info in FRAMES]
    status, out, err = run_cli([str(pcap), "-n"])
    assert status == 0, err
    assert [line[34:].split(" [")[0] for line in out.splitlines()] == [f"{name} {info}" for _, name, info in FRAMES]
