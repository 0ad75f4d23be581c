"""Records of no byte inside a capture (other writers; live -w writes one at its end: test_live_capture_end.py).

A record of no byte is no frame and no noise, and breaks nothing: a frame whose bytes are split across
records with an empty one between them is read whole, a request and its answer with one between them are
paired, and the capture's end is its last record, empty or not (Source.recorded_until). Classic pcap
(the engine's bulk scan, scan_pcap, and the Python reader) and pcapng, engine and VW3_PURE_PYTHON=1,
and the plugin (tshark -2): it shows nothing of its own for such a record, and -V/--json account for every
byte, their offsets end to end.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.model import Stamp
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter
from live_bus import ROOT
from lua_compare import compare
from lua_harness import lua_items, place_items, run_tshark

pytestmark = pytest.mark.integration
REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("010304000100022A32")
T0 = 1_767_225_600_000_000  # us
# (bytes, us after T0): an empty record between a request and its answer, another between the halves of
# a request, one after the last request, then the last record, empty, 300 ms after that request.
RECORDS = [(REQUEST, 0), (b"", 5_000), (ANSWER, 10_000), (b"", 500_000), (REQUEST[:4], 1_000_000),
           (b"", 1_000_300), (REQUEST[4:], 1_000_400), (ANSWER, 1_010_000), (REQUEST, 1_200_000),
           (b"", 1_300_000), (b"", 1_500_000)]
LINES = [
    "     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok",
    "     3     1.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     4     1.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#3, 10.0 ms]  CRC ok",
    "     5     1.200000   1 request   Read Holding Registers 0..1 (2) [the capture ends 300.0 ms after the "
    "request, within the 1000 ms timeout: not known whether it was answered]  CRC ok",
]


def capture(tmp_path: Path, suffix: str) -> Path:
    path = tmp_path / f"inside.{suffix}"
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False) if suffix == "pcapng" else PcapWriter(stream, flush=False)
        for data, micros in RECORDS:
            writer.write(data, Stamp((T0 + micros) * 1000))
    return path


def run(path: Path, pure: bool, *options: str, profiles: bool = False) -> str:
    """vw3-decode's output (-n unless `profiles`: profile auto, the plugin's default)."""
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    command = [sys.executable, "-m", "dissector", *([] if profiles else ["-n"]), *options, str(path)]
    done = subprocess.run(command, cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and not done.stderr, done.stderr
    return done.stdout


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_every_engine_reads_through_them(tmp_path: Path, suffix: str, pure: bool) -> None:
    path = capture(tmp_path, suffix)
    assert run(path, pure).splitlines() == LINES
    items = [json.loads(text) for text in run(path, pure, "--json").splitlines()]
    assert [(item["offset"], item["length"]) for item in items] == [(0, 8), (8, 9), (17, 8), (25, 9), (34, 8)]
    verbose = run(path, pure, "-V")
    assert [text for text in verbose.splitlines() if text.startswith("Frame ")] == [
        "Frame 1: 8 bytes at offset 0, request (RTU)", "Frame 2: 9 bytes at offset 8, response (RTU)",
        "Frame 3: 8 bytes at offset 17, request (RTU)", "Frame 4: 9 bytes at offset 25, response (RTU)",
        "Frame 5: 8 bytes at offset 34, request (RTU)"]


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_the_plugin_shows_nothing_for_them(tmp_path: Path, suffix: str) -> None:
    path = capture(tmp_path, suffix)
    fields = run_tshark(path, "-T", "fields", "-E", "separator=;", "-e", "frame.len", "-e", "vw3.kind",
                        "-e", "vw3.response_frame", "-e", "vw3.note")
    assert fields.returncode == 0, fields.stderr[-2000:]
    assert fields.stdout.splitlines() == [
        "8;1;3;", "0;;;", "9;2;;", "0;;;", "4;;;", "0;;;", "4;1;8;", "9;2;;",
        "8;1;;the capture ends 300.0 ms after the request, within the 1000 ms timeout: not known whether it "
        "was answered", "0;;;", "0;;;"]
    python = place_items([json.loads(text) for text in run(path, False, "--json", profiles=True).splitlines()],
                         [len(data) for data, _ in RECORDS])
    differences = compare(python, lua_items(path)[0])
    assert not differences, "\n".join(differences[:20])
