"""vw3-decode -V as the plugin's tree: a one-byte LRC shown as one byte; FC43/14's MEI type, read code and
conformity named from the spec's tables (data/modbus.toml), the number kept beside the name."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def decode(*args: str) -> str:
    done = subprocess.run([sys.executable, "-m", "dissector", *args], cwd=ROOT, capture_output=True, text=True,
                          check=True)
    return done.stdout


def test_ascii_lrc_is_one_byte() -> None:
    lines = decode("-V", "--hex", ":010300000001FB\r\n").splitlines()
    assert "        LRC: 0xFB [LRC ok]" in lines
    bad = decode("-V", "--hex", ":010300000001FA\r\n").splitlines()
    assert "        LRC: 0xFA [LRC BAD (received 0xFA, expected 0xFB)]" in bad
