"""Modbus ASCII live: a silence cuts neither a frame nor a noise run, as in the decode of the -w file.

An ASCII frame ends at its LF and may hold a second's silence (timing.ASCII_LIMIT); the decode of a file
cuts neither a frame nor a noise run at a silence (framing/stream.py _add_noise). Live closed what its
framer held after 250 ms of silence (CaptureThread.flush_due): a frame paused in was two noise runs live,
one request in the file; noise on both sides of a pause two runs live, one in the file. On a
pseudo-terminal (tests/support/live_bus.py), live --json against the -w file decoded by the engine, by the
Python stages and by the plugin (tshark -2).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.protocol.crc import lrc
from live_bus import ROOT, run_live_on_pty
from lua_compare import compare
from lua_harness import lua_items, python_items

pytestmark = pytest.mark.integration
OPTIONS = ["-n", "--mode", "ascii", "--json", "--timeout", "5"]  # (the answers below come within it)


def line(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


READ, ANSWER = line("010300000001"), line("0103020007")


def live_and_file(tmp_path: Path, writes: list[tuple[bytes, float]]) -> tuple[list[dict], Path]:
    path = tmp_path / "ascii.pcap"
    out, err, status = run_live_on_pty(writes, [*OPTIONS, "-w", str(path)])
    assert status == 0, err
    live = [json.loads(text) for text in out.decode().splitlines()]
    for env in ({}, {"VW3_PURE_PYTHON": "1"}):
        done = subprocess.run([sys.executable, "-m", "dissector", *OPTIONS, str(path)], cwd=ROOT,
                              env=dict(os.environ, **env), capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        assert [json.loads(text) for text in done.stdout.splitlines()] == live
    differences = compare(python_items(path, None, "--timeout", "5"), lua_items(path, "-o", "vw3.timeout_ms:5000")[0])
    assert not differences, "\n".join(differences[:20])
    return live, path


@pytest.mark.parametrize("pause", [0.5, 1.2])
def test_a_pause_inside_a_frame(tmp_path: Path, pause: float) -> None:
    """The request paused in after ':0103' is one request, answered, live and in the file."""
    live, _ = live_and_file(tmp_path, [(READ[:5], pause), (READ[5:], 0.05), (ANSWER, 0.1)])
    assert [(item["kind"], item["raw"], item.get("response_frame"), item["warnings"]) for item in live] == [
        ("request", READ.hex(), 2, []), ("response", ANSWER.hex(), None, [])]


def test_noise_on_both_sides_of_a_pause(tmp_path: Path) -> None:
    live, _ = live_and_file(tmp_path, [(b"ab", 0.5), (b"cd", 0.5), (READ, 0.05), (ANSWER, 0.1)])
    assert [(item["kind"], item["raw"], item.get("reason")) for item in live] == [
        ("noise", b"abcd".hex(), "outside an ASCII frame"), ("request", READ.hex(), None),
        ("response", ANSWER.hex(), None)]


def test_a_frame_the_stop_cuts(tmp_path: Path) -> None:
    """A frame begun when the capture stops: cut off by its end, live and in the file."""
    live, _ = live_and_file(tmp_path, [(READ, 0.05), (ANSWER, 0.1), (READ[:7], 0.4)])
    assert [(item["kind"], item["raw"], item.get("reason")) for item in live] == [
        ("request", READ.hex(), None), ("response", ANSWER.hex(), None),
        ("noise", READ[:7].hex(), "ASCII frame cut off by the end of the capture")]
