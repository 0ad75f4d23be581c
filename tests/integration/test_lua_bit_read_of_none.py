"""The plugin's Info and tree for a bit read's answer (FC1, FC2) of byte count 0, without its request:
`(0)` and `[Quantity: 0]`, as FC3's and as vw3-decode's summary (tests/unit/test_bit_read_of_none.py); with
its request the window asked. Real tshark with -X lua_script:lua/vw3.lua, -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    ("01 01 00", "1 Read Coils response (0)", "Read Coils (0)"),
    ("01 02 00", "1 Read Discrete Inputs response (0)", "Read Discrete Inputs (0)"),
    ("01 03 00", "1 Read Holding Registers response (0)", "Read Holding Registers (0)"),
    ("01 01 0000 0008", "1 Read Coils request 0..7 (8)", "Read Coils 0..7 (8)"),
    ("01 01 00", "1 Read Coils response 0..7 (8)", "Read Coils 0..7 (8)"),
]


def test_info_and_quantity_as_vw3_decode(tmp_path: Path) -> None:
    # (a second apart: each answer unpaired but the last)
    pcap = write_pcap(tmp_path / "none.pcap", [(rtu(frame), 1000.0 + k) for k, (frame, _, _) in enumerate(FRAMES)])
    result = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", "-e", "vw3.quantity")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == [f"{info}\t{8 if '(8)' in info else 0}" for _, info, _ in FRAMES]
    status, out, err = run_cli([str(pcap), "-n", "--timeout", "2"])
    assert status == 0, err
    assert [line[34:].split(" [")[0].split("  CRC")[0] for line in out.splitlines()] == [s for _, _, s in FRAMES]
