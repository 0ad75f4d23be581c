"""The hunt's Info texts (session 52), alike in vw3-decode (compiled engine and VW3_PURE_PYTHON=1) and the
plugin under real tshark 4.0: an FC24 answer of more values than a summary shows ends with how many more
(`… (+2)`, as register lists say it); an empty FIFO is `0 values`, no colon after it."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0  # 2026-01-01 00:00:00 UTC; one record a second
RECORDS = [
    # the hunt's: pointer 1246, 10 values (8 shown)
    bytes.fromhex("11 18 04 de 07 87"),
    bytes.fromhex("11 18 00 16 00 0a 00 00 00 64 00 c8 01 2c 01 90 01 f4 02 58 02 bc 03 20 03 84 9e 09"),
    rtu("11 18 04de"), rtu("11 18 0002 0000"),  # an empty FIFO
]
INFO = [
    ("request", "Read FIFO Queue pointer 1246"),
    ("response", "Read FIFO Queue 10 values: 0 100 200 300 400 500 600 700 … (+2)"),
    ("request", "Read FIFO Queue pointer 1246"),
    ("response", "Read FIFO Queue 0 values"),
]
TAILS = {1: " [#1, 1000.0 ms]", 3: " [#3, 1000.0 ms]"}


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("hunt_describe") / "hunt.pcap",
                      [(data, T0 + at) for at, data in enumerate(RECORDS)])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_info(capture: Path, pure: bool) -> None:
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    else:  # a missing engine would run the Python stages twice
        from dissector.accel import fastsummary
        assert fastsummary.available() and fastsummary.built(), "the compiled engine is not built"
    result = subprocess.run([sys.executable, "-m", "dissector", str(capture)], capture_output=True, text=True,
                            env=env, cwd=ROOT, timeout=300)
    assert (result.returncode, result.stderr) == (0, "")
    assert result.stdout.splitlines() == [
        f"{index + 1:>6} {index:>12.6f}  17 {kind:<9} {info}{TAILS.get(index, '')}  CRC ok"
        for index, (kind, info) in enumerate(INFO)]


def test_plugin_info(capture: Path) -> None:
    result = run_tshark(capture, "-T", "fields", "-e", "_ws.col.Info")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    names = len("Read FIFO Queue ")
    assert result.stdout.splitlines() == [f"17 Read FIFO Queue {kind} {info[names:]}" for kind, info in INFO]
