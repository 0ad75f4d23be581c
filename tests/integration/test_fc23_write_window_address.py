"""`-Y 'address == 5'` finds an FC23 request that writes none at 5 (`read 0, write 5 (0)`), as it finds FC16's
of quantity 0 at 5 (`5 (0)`), FC6's at 5 and an FC23 writing a value at 5: the frame names its written
window's start, so it is an address the frame names (was: only its read window's). Its answer, which carries
the read values alone, still does not. The plugin's hidden vw3.reg.address (and vw3.reg.label, PLC style)
names the same addresses, once each, as vw3-decode's -T fields -e address; vw3-decode under the compiled
engine and VW3_PURE_PYTHON=1; real tshark with -X lua_script:lua/vw3.lua, -2."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    ("01 17 0000 0001 0005 0000 00", "0,5"),  # 1 FC23 writing none at 5
    ("01 17 02 0007", "0"),  # 2 its answer: the read values
    ("01 17 0000 0001 0005 0001 02 0009", "5,0"),  # 3 FC23 writing 9 at 5 (the value, then the read window)
    ("01 17 02 0007", "0"),  # 4
    ("01 17 0005 0002 0006 0000 00", "5,6"),  # 5 writing none at 6, inside its read window: named once
    ("01 17 04 0007 0008", "5,6"),  # 6
    ("01 10 0005 0000 00", "5"),  # 7 FC16 writing none at 5
    ("01 10 0005 0000", "5"),  # 8
    ("01 06 0005 0009", "5"),  # 9 FC6 at 5
    ("01 06 0005 0009", "5"),  # 10
    ("01 17 0000 0001 0009 0000 00", "0,9"),  # 11 writing none elsewhere
    ("01 17 02 0007", "0"),  # 12
]
AT_5 = [1, 3, 5, 6, 7, 8, 9, 10]
PLC = ("-o", "vw3.profiles:generic", "-o", "vw3.address_style:plc")


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("fc23") / "fc23.pcap",
                      [(rtu(frame), 1000.0 + k) for k, (frame, _) in enumerate(FRAMES)])


def vw3_decode(pcap: Path, pure: bool, *args: str) -> str:
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    result = subprocess.run([sys.executable, "-m", "dissector", str(pcap), *args], capture_output=True, text=True,
                            env=env, cwd=ROOT, timeout=300)
    assert (result.returncode, result.stderr) == (0, "")
    return result.stdout


def tshark(pcap: Path, *args: str) -> str:
    result = run_tshark(pcap, *args)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode_finds_the_written_start(capture: Path, pure: bool) -> None:
    assert vw3_decode(capture, pure, "-Y", "address == 5", "-T", "fields", "-e", "frame").split() == [
        str(n) for n in AT_5]
    assert vw3_decode(capture, pure, "-T", "fields", "-e", "address").splitlines() == [
        addresses for _, addresses in FRAMES]


def test_plugin_names_the_same_addresses(capture: Path) -> None:
    assert tshark(capture, "-Y", "vw3.reg.address == 5", "-T", "fields", "-e", "frame.number").split() == [
        str(n) for n in AT_5]
    assert tshark(capture, "-T", "fields", "-e", "vw3.reg.address").splitlines() == [
        addresses for _, addresses in FRAMES]


def test_plc_labels_of_the_written_start(capture: Path) -> None:
    plc = ["--profile", "generic", "--address-style", "plc"]
    assert vw3_decode(capture, False, *plc, "-Y", 'label == "40006"', "-T", "fields", "-e", "frame").split() == [
        str(n) for n in AT_5]
    assert tshark(capture, *PLC, "-Y", 'vw3.reg.label == "40006"', "-T", "fields", "-e", "frame.number").split() == [
        str(n) for n in AT_5]
    assert tshark(capture, *PLC, "-Y", "frame.number == 1", "-T", "fields", "-e", "vw3.reg.label").split() == [
        "40001,40006"]
