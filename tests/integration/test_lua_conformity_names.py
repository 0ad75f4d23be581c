"""The plugin names FC43/14's conformity level (Application Protocol 6.21; data/modbus.toml
[names.device_id_conformity], named by data/pdu_fields.toml's conformity field) as vw3-decode -V does
(tests/unit/test_detail_names.py). Before: `Conformity: 131 (0x83)`. Real tshark with lua/vw3.lua."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0


def test_conformity_is_named(tmp_path: Path) -> None:
    frames = [rtu("0C 2B 0E 01 00"), rtu("0C 2B 0E 01 83 00 00 01 00 03 41 42 43"),
              rtu("0C 2B 0E 01 00"), rtu("0C 2B 0E 01 05 00 00 01 00 03 41 42 43")]
    pcap = write_pcap(tmp_path / "fc43.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    lines = [line.strip() for line in result.stdout.splitlines()]
    assert [line for line in lines if line.startswith(("MEI type:", "Read code:", "Conformity:"))] == [
        "MEI type: Read Device Identification (14)", "Read code: basic (1)",
        "MEI type: Read Device Identification (14)", "Read code: basic (1)",
        "Conformity: extended, stream and individual access (131)",
        "MEI type: Read Device Identification (14)", "Read code: basic (1)",
        "MEI type: Read Device Identification (14)", "Read code: basic (1)", "Conformity: Unknown (5)",
    ]
