"""The plugin's `baud` preference is vw3-decode's --baud: the line speed whose t3.5 of silence before a record
ends a run of noise (lua/src/stream.lua lane.line_speed, add_noise; framing/stream.py). Without it the plugin
took 19200 baud's t3.5 whatever the line: on a 9600-baud bus its noise items were not `vw3-decode --baud
9600`'s. Records of 3 noise bytes 5, 2.2 and 20 ms apart: at 9600 baud only the 20 ms gap is a silence
(3 characters take 3.4 ms, t3.5 is 4.0 ms), at 19200 the 5 and 20 ms ones (1.7 ms, 2.0 ms), at 115200 all
three (t3.5 fixed at 1.75 ms). Exact Info with -2, every field as vw3-decode --baud says it."""
from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from dissector.framing.timing import DEFAULT_BAUD
from lua_compare import compare
from lua_harness import ROOT, lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
NOISE = bytes.fromhex("ff00aa")
TIMES = [0.0, 0.005, 0.0072, 0.0272]
CONTINUE = "(3 bytes of noise in #3)"  # (noise shown in record 3: bytes that continue no frame)
INFOS = {
    9600: [CONTINUE, CONTINUE, "noise (9 bytes)", "noise (3 bytes)"],
    19200: ["noise (3 bytes)", CONTINUE, "noise (6 bytes)", "noise (3 bytes)"],
    115200: ["noise (3 bytes)"] * 4,
}


def _capture(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "noise.pcap", [(NOISE, 1700000000 + time) for time in TIMES])


def _infos(pcap: Path, *options: str) -> list[str]:
    got = run_tshark(pcap, *options, "-T", "fields", "-e", "_ws.col.Info")
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


@pytest.mark.parametrize("baud", sorted(INFOS))
def test_the_preference_cuts_noise_as_vw3_decode_baud(tmp_path: Path, baud: int) -> None:
    pcap = _capture(tmp_path)
    option = f"vw3.baud:{baud}"
    assert _infos(pcap, "-o", option) == INFOS[baud]
    python = python_items(pcap, None, "--baud", str(baud))
    # (vw3-decode's noise items at that speed: one a record the plugin shows one in)
    assert len({item.data["frame"] for item in python}) == sum(info.startswith("noise") for info in INFOS[baud])
    differences = compare(python, lua_items(pcap, "-o", option)[0])
    assert not differences, "\n".join(differences[:40])


def test_without_the_preference_as_vw3_decode_without_baud(tmp_path: Path) -> None:
    pcap = _capture(tmp_path)
    catalogue = tomllib.loads((ROOT / "dissector" / "data" / "fields.toml").read_text(encoding="utf-8"))
    (baud,) = [entry for entry in catalogue["preference"] if entry["name"] == "baud"]
    assert baud["default"] == DEFAULT_BAUD
    assert _infos(pcap) == INFOS[DEFAULT_BAUD]
    assert not compare(python_items(pcap), lua_items(pcap)[0])
    # A speed --baud refuses (0, below 50 baud, above 4,000,000) is its default's.
    for refused in (0, 49, 4000001):
        assert _infos(pcap, "-o", f"vw3.baud:{refused}") == INFOS[DEFAULT_BAUD]
