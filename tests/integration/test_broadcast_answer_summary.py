"""A slave answering a broadcast (hunt 56, pymodbus 3.16.1 answering mbpoll's FC6 to slave 0 with exception 04)
is said once in the summary: the warning names the broadcast it answers, so no `[no request]` beside it
(before: both), under the compiled engine and VW3_PURE_PYTHON=1. An answer from slave 0 with no broadcast
before it keeps `[no request]`. -V, --json and the plugin's tree say the warning alone too."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import engine_output_as_python, rtu
from lua_harness import lua_errors, run_tshark, write_pcap

ROOT = Path(__file__).resolve().parents[2]
WARNING = "response from slave 0 after broadcast #1: no server answers a broadcast"
FRAMES = [rtu("00 06 0005 0001"), rtu("00 86 04")]


def test_summary_says_it_once(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python([arg for frame in FRAMES for arg in ("--hex", frame.hex())], monkeypatch)
    assert out.splitlines()[1] == (
        "     2            -   0 exception Write Single Register: exception 4 (Server Device Failure)"
        f" [warning: {WARNING}]  CRC ok")


def test_an_answer_from_slave_0_without_a_broadcast_has_no_request(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python(["--hex", rtu("00 86 04").hex()], monkeypatch)
    assert "[no request] [response without a matching request in the capture] [warning: response from slave 0," in out


def test_json_verbose_and_plugin_say_the_warning(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "b.pcap", [(frame, 1767225600.0 + 0.01 * index) for index, frame in enumerate(FRAMES)])
    run = [sys.executable, "-m", "dissector"]
    record = json.loads(subprocess.run(run + ["--json", str(pcap)], cwd=ROOT, capture_output=True, text=True,
                                       check=True).stdout.splitlines()[1])
    assert (record["warnings"], record["notes"], "request_frame" in record) == ([WARNING], [], False)
    verbose = subprocess.run(run + ["-V", str(pcap)], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    assert verbose.rstrip().endswith(f"CRC: 0x6312 [CRC ok]\n    Warning: {WARNING}")
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert f"    [Warning: {WARNING}]" in result.stdout and "no request" not in result.stdout
