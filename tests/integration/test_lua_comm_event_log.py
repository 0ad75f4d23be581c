"""The plugin's tree names FC12's events as vw3-decode -V does (decode/fields.py comm_event; data/modbus.toml
[names.comm_event*], as Wireshark's modbus dissector names them): before, `Events: 200004c27f80` alone. Real
tshark, under the same lines as -V's event list."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
T0 = 1767225600.0
FRAMES = [rtu("01 0C"), rtu("01 0C 0C FFFF 0108 0121 20 00 04 C2 7F 80")]


def _events(text: str) -> list[str]:
    lines = text.splitlines()
    start = next(index for index, line in enumerate(lines) if line.strip().startswith("Events: "))
    depth = len(lines[start]) - len(lines[start].lstrip())
    out = [lines[start].strip()]
    for line in lines[start + 1 :]:
        if len(line) - len(line.lstrip()) < depth or line.strip().startswith(("CRC", "[Request")):
            break
        out.append(" " * (len(line) - len(line.lstrip()) - depth) + line.strip())
    return out


def test_the_plugin_names_each_event_as_vw3_decode(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc12.pcap", [(frame, T0 + 0.010 * index) for index, frame in enumerate(FRAMES)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    wanted = _events(python)
    # (a receive event of no flag, 0x80: its four bits each 0, as tshark -V lists them; `Flags (0)` alone before)
    assert len(wanted) == 37 and wanted[1] == "Event list (6)" and wanted[-5:] == [
        "        Flags", "            .... ..0. = Communication Error: 0", "            ...0 .... = Character Overrun: 0",
        "            ..0. .... = Currently in Listen Only Mode: 0", "            .0.. .... = Broadcast Received: 0"]
    assert _events(result.stdout) == wanted
