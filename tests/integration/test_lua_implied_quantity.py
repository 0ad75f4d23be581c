"""vw3-decode -V shows the quantity of one of FC5's, FC6's and FC22's window, `[Quantity: 1]` after the address,
as --json's `quantity` says it and the plugin's tree shows it (before: -V alone left it out). Its bytes do not
count it (data/modbus.toml [lift] quantity = 1): in brackets, as the plugin's generated item. A read's answer
without its request shows the quantity its byte count gives, `[Quantity: 2]` (before: none in -V). Real
tshark."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = ["01 05 00AC FF00", "01 05 00AC FF00", "01 06 0028 0025", "01 06 0028 0025", "01 16 0028 00F2 0025",
          "01 03 0000 0001"]


def _after_address(text: str) -> list[str]:
    lines = [line.strip() for line in text.splitlines()]
    return [lines[index + 1] for index, line in enumerate(lines) if line.startswith("Address:")]


def test_quantity_of_one_in_every_output(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", [(rtu(frame), 1767225600 + 0.01 * index)
                                              for index, frame in enumerate(FRAMES)])

    def run(*options: str) -> str:
        return subprocess.run([sys.executable, "-m", "dissector", *options, str(pcap)], cwd=ROOT,
                              capture_output=True, text=True, check=True).stdout

    assert [json.loads(line).get("quantity") for line in run("--json").splitlines()] == [1, 1, 1, 1, 1, 1]
    assert _after_address(run("-V")) == ["[Quantity: 1]"] * 5
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert _after_address(result.stdout) == ["[Quantity: 1]"] * 5


def test_an_answer_without_its_request(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "alone.pcap", [(rtu("01 04 04 0001 0002"), 1767225600.0)])
    python = subprocess.run([sys.executable, "-m", "dissector", "-V", str(pcap)], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    for text in (python, result.stdout):
        assert [line.strip() for line in text.splitlines() if line.strip().startswith("[Quantity")] == [
            "[Quantity: 2]"]
