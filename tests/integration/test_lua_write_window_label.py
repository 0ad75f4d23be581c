"""The plugin with address_style plc labels FC23's written window as vw3-decode does
(tests/unit/test_write_window_label.py): its Info `read 40001, write 40006 (0)` (was `write 5 (0)`, the
protocol number), `write 40006` where it writes a value (its values left out by design), and
vw3.write_span_label, as vw3-decode's -T fields writes write_span_label. Real tshark with
-X lua_script:lua/vw3.lua, -2."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

PLC = ("-o", "vw3.profiles:generic", "-o", "vw3.address_style:plc")
FRAMES = [
    ("01 17 0000 0001 0005 0000 00", "read 40001, write 40006 (0)", "40006"),
    ("01 17 0000 0002 0005 0003 00", "read 40001..40002 (2), write 40006..40008 (3)", "40006..40008"),
    ("01 17 0000 0001 0005 0001 02 0007", "read 40001, write 40006", "40006"),
    ("01 17 0000 0001 0005 0000 00", "read 40001, write 40006 (0)", "40006"),  # (met again: a quick lane's)
]


def test_info_and_field(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc23.pcap", [(rtu(frame), 1000.0 + 2 * k) for k, (frame, _, _) in enumerate(FRAMES)])
    result = run_tshark(pcap, *PLC, "-T", "fields", "-e", "_ws.col.Info", "-e", "vw3.write_span_label")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == [
        f"1 Read/Write Multiple Registers request {info}\t{label}" for _, info, label in FRAMES]
    status, out, err = run_cli([str(pcap), "--profile", "generic", "--address-style", "plc",
                                "-T", "fields", "-e", "write_span_label"])
    assert status == 0, err
    assert out.splitlines() == [label for _, _, label in FRAMES]
