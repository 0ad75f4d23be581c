"""Every other output of a timed capture framed in C (dissector/accel/framespath.py) against the Python
stages (VW3_PURE_PYTHON=1): -V, --json, -T fields, --stats, -Y, -c, -x and -w byte for byte, on pcap and
pcapng files cut at random, with times and damage (the same captures as test_timed_summary.py)."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from dissector.sim.simulate import generate_session
from test_timed_summary import assert_same, cut_records, frames_of, write_pcap, write_pcapng

OUTPUTS = [
    ["--json"],
    ["-V"],
    ["-T", "fields", "-e", "frame", "-e", "time_relative", "-e", "time_delta", "-e", "response_time", "-e", "slave",
     "-e", "function_name", "-e", "request_frame", "-e", "registers"],
    ["--stats"],
    ["-Y", "slave == 12 or kind == \"noise\""],
    ["-c", "150", "--json"],
    ["-x", "-t", "d"],
    ["--stats", "--json", "--timeout", "0.03"],
]


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("output", range(len(OUTPUTS)))
def test_random_captures_same_outputs(seed: int, output: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed * 31 + output)
    frames = frames_of(seed + 100, damaged=0.0 if seed == 0 else 0.06)
    records = cut_records(rng, frames, ["frame", "bursts", "untimed", "frame"][seed])
    capture = tmp_path / ("bus.pcapng" if seed == 3 else "bus.pcap")
    (write_pcapng if seed == 3 else write_pcap)(capture, records)  # type: ignore[operator]
    assert_same([str(capture), *OUTPUTS[output]], monkeypatch)


def test_polling_pcap_outputs_and_w(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A healthy bus (the engine frames nearly all of it): -V, --json, --stats; -w writes the same file."""
    records = generate_session(800, seed=9)
    capture = tmp_path / "polling.pcap"
    write_pcap(capture, [(data, round(time * 1e9)) for data, time in records], nano=False)
    for output in (["-V"], ["--json"], ["--stats"], ["--profile", "atv71", "-T", "fields", "-e", "frame", "-e", "registers"]):
        assert_same([str(capture), *output], monkeypatch)
    written = {}
    for pure in (False, True):
        out = tmp_path / f"out{pure}.pcapng"
        assert_same([str(capture), "-w", str(out), "-Y", "slave == 1"], monkeypatch)
        written[pure] = out.read_bytes()
    assert written[False] == written[True]
