"""-w writes a pcap that decodes to the same frames, and that Wireshark's own mbrtu dissector reads alike."""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import ensure_tool

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = sorted((ROOT / "captures").glob("*.bin"))
TSHARK_OPTIONS = [
    "-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""',
    "-o", "mbrtu.crc_verification:TRUE",
]
SAME = ("kind", "slave", "function", "raw", "crc_ok", "registers", "request_frame", "exception_code")


def decode_json(path: Path, *options: str) -> list[dict]:
    status, out, err = run_cli([str(path), "--json", *options])
    assert status == 0, err
    return [json.loads(line) for line in out.splitlines()]


def test_there_are_sample_captures() -> None:
    names = {path.stem for path in CAPTURES}
    assert {"p38_protection", "atv71_commissioning", "sel749m_polling", "noisy_bus", "ascii_session"} <= names


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.stem)
def test_write_then_read_gives_the_same_frames(capture: Path, tmp_path: Path) -> None:
    pcap = tmp_path / "out.pcap"
    status, out, err = run_cli([str(capture), "-w", str(pcap)])
    assert (status, out) == (0, ""), err  # -w alone prints nothing, as tshark
    original = decode_json(capture)
    again = decode_json(pcap)
    assert len(again) == len(original)
    for before, after in zip(original, again):
        assert {key: before.get(key) for key in SAME} == {key: after.get(key) for key in SAME}


@pytest.mark.parametrize("capture", [c for c in CAPTURES if c.stem != "ascii_session"], ids=lambda path: path.stem)
def test_tshark_mbrtu_agrees_on_slave_function_and_crc(capture: Path, tmp_path: Path) -> None:
    tshark = ensure_tool("tshark", "tshark")
    pcap = tmp_path / "out.pcap"
    assert run_cli([str(capture), "-w", str(pcap)])[0] == 0
    ours = decode_json(capture)
    result = subprocess.run(
        [tshark, "-r", str(pcap), *TSHARK_OPTIONS, "-T", "fields", "-E", "separator=;",
         "-e", "frame.number", "-e", "mbrtu.unit_id", "-e", "modbus.func_code", "-e", "mbrtu.crc16.status"],
        capture_output=True, text=True, timeout=300,
    )
    assert result.returncode == 0, result.stderr
    rows = [line.split(";") for line in result.stdout.splitlines()]
    assert len(rows) == len(ours)
    compared = 0
    for item, (number, unit, function, crc_status) in zip(ours, rows):
        if item["kind"] == "noise" or not function:
            continue  # noise records, and frames tshark cannot classify (FC5/6/8/43...)
        assert int(number) == item["frame"]
        assert int(unit) == item["slave"]
        assert int(function) & 0x7F == item["function"]
        assert crc_status == ("1" if item["crc_ok"] else "0"), item
        compared += 1
    assert compared >= len([item for item in ours if item["kind"] != "noise"]) // 2
