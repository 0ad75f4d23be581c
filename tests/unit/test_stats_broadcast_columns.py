"""--stats' traffic table keeps its columns under their headers with a broadcast row (hunt 56: pymodbus
answering mbpoll's broadcast FC6): slave 0's requests are broadcasts, said once in the caption, where a
`1 (1 broadcast)` cell widened the req column past every other row's number (plain) and was cut to
`1 (1 broadcast` with the headers squeezed to `sla`, `re` (rich, 80 columns). Compiled engine = pure."""
from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT
from helpers import engine_output_as_python, rtu

FRAMES = [rtu("00 06 0005 0001"), rtu("01 03 0000 0001"), rtu("01 03 02 0007"),
          rtu("43 2B 0E 01 00"), rtu("43 AB 01")]
ARGV = ["--stats"] + [arg for frame in FRAMES for arg in ("--hex", frame.hex())]
TABLE = [
    "Traffic per slave and function",
    "slave  function                             req  resp  exceptions  no reply  bad CRC",
    "-" * 84,
    "    0  6 Write Single Register                1     0                     0        0",
    "    1  3 Read Holding Registers               1     1                     0        0",
    "   67  43 Encapsulated Interface Transport    1     0  01:1               0        0",
    "req: requests (to slave 0: broadcasts), resp: normal responses, exceptions: code:count (hex code)",
]


def _traffic(out: str) -> list[str]:
    lines = [line.rstrip() for line in out.splitlines()]
    start = lines.index("Traffic per slave and function")
    return lines[start : lines.index("", start)]


def test_plain_columns_stay_under_their_headers(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python(ARGV, monkeypatch)
    assert _traffic(out) == TABLE


def test_rich_at_80_columns_keeps_its_headers() -> None:
    env = dict(os.environ, COLUMNS="80", PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-m", "dissector", "--color", "always", *ARGV], cwd=ROOT, env=env,
                         capture_output=True, text=True, check=True).stdout
    table = _traffic(re.sub(r"\x1b\[[0-9;]*m", "", out))
    assert table[1] == " slave  function                      req  resp  exceptions  no reply  bad CRC"
    assert table[3] == "     0  6 Write Single Register         1     0                     0        0"
    assert table[-2:] == ["req: requests (to slave 0: broadcasts), resp: normal responses, exceptions:",
                          "code:count (hex code)"]
