"""The plugin's Info column says FC6's value as vw3-decode's summary does (hunt 55 S2): `5 = 48879`, not `5`
alone; where the slave's device names the register or reads the value as a text, as the device names it
(`3103 TFR=50.0 Hz`, `8401 CHCF=IO (I/O profile)`, an echo that differs `8502 LFR=-5.0 Hz`), PLC style as
its label (`40002 = 3`), RTU and ASCII, broadcast, tshark -2 and one pass, a request met again (the quick
lane of known requests) alike. Real tshark 4.0 with -X lua_script:lua/vw3.lua."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0  # 2026-01-01 00:00:00 UTC; one record a second


def ascii_frame(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([-sum(body) & 0xFF])).hex().upper().encode() + b"\r\n"


# (profile, frames, the plugin's Info of each, in -2 and in one pass)
CASES = {
    "generic": ("", ["01 06 0005 BEEF", "01 06 0005 BEEF", "00 06 0001 0003"] * 2,
                ["1 Write Single Register request 5 = 48879", "1 Write Single Register response 5 = 48879",
                 "0 Write Single Register request 1 = 3"] * 2),
    "atv71": ("atv71", ["0C 06 0C1F 01F4", "0C 06 0C1F 01F4", "0C 06 20D1 0003", "0C 06 20D1 0003",
                        "0C 06 20D5 0009", "0C 06 2136 FFCE", "0C 06 0C1F 01F4", "0C 06 0C1F 01F4"],
              ["12 Write Single Register request 3103 TFR=50.0 Hz",
               "12 Write Single Register response 3103 TFR=50.0 Hz",
               "12 Write Single Register request 8401 CHCF=IO (I/O profile)",
               "12 Write Single Register response 8401 CHCF=IO (I/O profile)",
               "12 Write Single Register request 8405 = 9",
               "12 Write Single Register response 8502 LFR=-5.0 Hz",
               "12 Write Single Register request 3103 TFR=50.0 Hz",
               "12 Write Single Register response 3103 TFR=50.0 Hz"]),
    "sel749m": ("sel749m", ["03 06 0001 0003", "03 06 0001 0003"],
                ["3 Write Single Register request 40002 = 3", "3 Write Single Register response 40002 = 3"]),
}


def _pcap(tmp_path: Path, name: str, ascii: bool) -> Path:
    frames = [ascii_frame(text) if ascii else rtu(text) for text in CASES[name][1]]
    return write_pcap(tmp_path / f"{name}.pcap", [(frame, T0 + index) for index, frame in enumerate(frames)])


def _summary_infos(pcap: Path, profile: str) -> list[str]:
    """vw3-decode's descriptions: the summary line from its function name to its tail or CRC."""
    argv = [sys.executable, "-m", "dissector", str(pcap), *(["--profile", profile] if profile else [])]
    out = subprocess.run(argv, capture_output=True, text=True, cwd=ROOT, timeout=300, check=True).stdout
    return [line[34:].split(" [")[0].split("  ")[0] for line in out.splitlines()]


@pytest.mark.parametrize("ascii", [False, True], ids=["rtu", "ascii"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_fc6_info_says_the_value_as_the_summary(tmp_path: Path, name: str, ascii: bool) -> None:
    profile, _frames, expected = CASES[name]
    pcap = _pcap(tmp_path, name, ascii)
    options = ["-o", f"vw3.profiles:{profile}"] if profile else []
    for two_pass in (True, False):
        # (Info alone, no tree: the first pass's lanes; -T fields with it: a tree)
        plain = run_tshark(pcap, *options, "-T", "tabs", two_pass=two_pass)
        fields = run_tshark(pcap, *options, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
        assert not lua_errors(plain.stdout + plain.stderr + fields.stdout + fields.stderr)
        infos = [line.split("\t")[-1] for line in plain.stdout.splitlines()]
        if not two_pass and name == "generic":  # (auto: slaves 1 and 0 read before any choice)
            expected = [f"{info} [provisional]" for info in expected]
        assert infos == expected
        assert fields.stdout.splitlines() == expected
    # vw3-decode says the same after the function's name
    plugin = [info.split(" ", 1)[1].replace(" request ", " ").replace(" response ", " ")
              for info in CASES[name][2]]
    assert _summary_infos(pcap, profile) == plugin
