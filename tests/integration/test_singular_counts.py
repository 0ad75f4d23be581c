"""A count of one in the Info text is singular, as describe.count_text says it everywhere else: FC11's
`1 event`, FC12's `1 event, 1 message`, FC24's `1 value: 7` (were `1 events`, `1 messages`, `1 values`), in
vw3-decode under the compiled engine and VW3_PURE_PYTHON=1 (byte for byte the same) and in the plugin's Info
(real tshark with -X lua_script:lua/vw3.lua). The count-with-noun step is stated once, in describe.TEXT_FORMS."""
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
    rtu("01 0B"), rtu("01 0B 0000 0001"),  # FC11: status 0, event count 1
    rtu("01 0C"), rtu("01 0C 06 0000 0001 0001"),  # FC12: status 0, 1 event, 1 message, no events listed
    rtu("01 18 0010"), rtu("01 18 0004 0001 0007"),  # FC24: one value, 7
    rtu("01 0C"), rtu("01 0C 06 0012 0002 0000"),  # FC12: 2 events, 0 messages (plural still)
]
INFO = [
    ("request", "Get Comm Event Counter"),
    ("response", "Get Comm Event Counter status 0x0000, 1 event"),
    ("request", "Get Comm Event Log"),
    ("response", "Get Comm Event Log status 0x0000, 1 event, 1 message"),
    ("request", "Read FIFO Queue pointer 16"),
    ("response", "Read FIFO Queue 1 value: 7"),
    ("request", "Get Comm Event Log"),
    ("response", "Get Comm Event Log status 0x0012, 2 events, 0 messages"),
]


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("singular") / "counts.pcap",
                      [(data, T0 + at) for at, data in enumerate(RECORDS)])


def vw3_decode(pcap: Path, pure: bool) -> str:
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    else:  # a missing engine would run the Python stages twice
        from dissector.accel import fastsummary
        assert fastsummary.available() and fastsummary.built(), "the compiled engine is not built"
    result = subprocess.run([sys.executable, "-m", "dissector", str(pcap)], capture_output=True, text=True,
                            env=env, cwd=ROOT, timeout=300)
    assert (result.returncode, result.stderr) == (0, "")
    return result.stdout


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_says_one_singular(capture: Path, pure: bool) -> None:
    lines = vw3_decode(capture, pure).splitlines()
    assert lines == [f"{index + 1:>6} {index:>12.6f}   1 {kind:<9} {info}"
                     f"{f' [#{index}, 1000.0 ms]' if index % 2 else ''}  CRC ok"
                     for index, (kind, info) in enumerate(INFO)]


def test_plugin_says_one_singular(capture: Path) -> None:
    result = run_tshark(capture, "-T", "fields", "-e", "_ws.col.Info")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    expected = []
    for kind, info in INFO:
        name = next(name for name in ("Get Comm Event Counter", "Get Comm Event Log", "Read FIFO Queue")
                    if info.startswith(name))
        expected.append(f"1 {name} {kind} {info[len(name) + 1:]}".rstrip())
    assert result.stdout.splitlines() == expected
