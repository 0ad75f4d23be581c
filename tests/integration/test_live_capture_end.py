"""Live and the decode of its -w file agree on the capture's end (live_capture.CaptureFiles.close).

A file holds no other sign of when its capture stopped: live -w ends it with a record of no byte at the
stop time (CaptureThread.stopped_at), which every reader takes as the capture's end (Source.recorded_until;
the plugin's recorded_until), and live's own finish uses the same time. So a request left unanswered when
the capture stops is judged alike: live --json, the -w file decoded by the engine, by the Python stages and
by the plugin (tshark -2). On a pseudo-terminal (tests/support/live_bus.py), stopped by SIGINT, at -c, and
by the adapter going away.
"""
from __future__ import annotations

import json
import os
import signal
import struct
import subprocess
import sys
import time
from pathlib import Path

import pytest

from dissector.protocol.crc import with_crc
from live_bus import ROOT, open_pty
from lua_compare import compare
from lua_harness import lua_items, place_items, run_tshark

pytestmark = pytest.mark.integration
READ = with_crc(bytes.fromhex("010300000001"))
ANSWER = with_crc(bytes.fromhex("0103020007"))
UNKNOWN = "the capture ends before any response: not known whether it was answered"
PURE = {"VW3_PURE_PYTHON": "1"}
# The plugin's fields of each record: frame length, kind, response frame, unanswered, notes.
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "frame.len", "-e", "vw3.kind", "-e", "vw3.response_frame",
          "-e", "vw3.unanswered", "-e", "vw3.note"]


def sniff(path: Path, writes: list[tuple[bytes, float]], options: list[str], env: dict[str, str],
          vanish: bool = False) -> tuple[list[dict], str]:
    """vw3-decode --live --json -w `path` on a pseudo-terminal `writes` go into ((bytes, pause after)):
    stopped by SIGINT after the last pause, or by the terminal going away (`vanish`); (its items, stderr)."""
    line, device, name = open_pty()
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", name, "-n", "--baud", "115200", "--json", "-w", str(path),
         "--timeout", "0.2", *options],
        cwd=ROOT, env=dict(os.environ, **env), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    try:
        assert process.stderr is not None and b"listening on" in process.stderr.readline()
        for data, pause in writes:
            os.write(line, data)
            time.sleep(pause)
        if vanish:
            os.close(device)  # (the sniffer's own descriptor stays: closing ours and the line's hangs it up)
            os.close(line)
            line = device = -1
        elif process.poll() is None:
            process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
        for fd in (line, device):
            if fd >= 0:
                os.close(fd)
    return [json.loads(text) for text in out.decode().splitlines()], err.decode()


def decoded(path: Path, env: dict[str, str], *options: str) -> list[dict]:
    done = subprocess.run([sys.executable, "-m", "dissector", *options, "--json", "--timeout", "0.2", str(path)],
                          cwd=ROOT, env=dict(os.environ, **env), capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return [json.loads(text) for text in done.stdout.splitlines()]


def record_times(path: Path) -> list[tuple[int, int]]:
    """(microseconds, captured length) of each record of a classic pcap or a pcapng of one interface
    (microsecond resolution, as vw3-decode writes both)."""
    data = path.read_bytes()
    out = []
    if data[:4] == bytes.fromhex("d4c3b2a1"):
        at = 24
        while at < len(data):
            seconds, micros, captured, _original = struct.unpack_from("<IIII", data, at)
            out.append((seconds * 1_000_000 + micros, captured))
            at += 16 + captured
        return out
    at = 0
    while at < len(data):
        kind, length = struct.unpack_from("<II", data, at)
        if kind == 6:  # an enhanced packet block
            _interface, high, low, captured = struct.unpack_from("<IIII", data, at + 8)
            out.append(((high << 32) | low, captured))
        at += length
    return out


def plugin_fields(path: Path) -> list[str]:
    result = run_tshark(path, "-o", "vw3.timeout_ms:200", *FIELDS)
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout.splitlines()


def check_one_truth(path: Path, live: list[dict]) -> list[dict]:
    """The -w file ends with a record of no byte, at or after its last; live's items are its decode's, by
    the engine and by the Python stages; the plugin's are its decode's."""
    records = record_times(path)
    assert records[-1][1] == 0 and all(length for _, length in records[:-1])
    assert records[-1][0] >= records[-2][0]
    engine, pure = decoded(path, {}, "-n"), decoded(path, PURE, "-n")
    assert engine == pure == live
    # (as lua_harness.python_items, of any format: profile auto, as the plugin's default)
    placed = place_items(decoded(path, {}), [length for _, length in records])
    differences = compare(placed, lua_items(path, "-o", "vw3.timeout_ms:200")[0])
    assert not differences, "\n".join(differences[:20])
    return engine


@pytest.mark.parametrize(("suffix", "env"), [("pcap", {}), ("pcapng", PURE)], ids=["pcap-engine", "pcapng-python"])
def test_stopped_within_the_timeout(tmp_path: Path, suffix: str, env: dict[str, str]) -> None:
    """Stopped before the timeout: not known whether it was answered, the wait measured to the stop by both."""
    path = tmp_path / f"within.{suffix}"
    live, err = sniff(path, [(READ, 0.1), (ANSWER, 0.1), (READ, 0.0)], [], env)
    assert "3 frames" in err, err
    items = check_one_truth(path, live)
    last = items[-1]
    assert last["unanswered"] is False and len(last["notes"]) == 1
    assert last["notes"][0].startswith("the capture ends ") and last["notes"][0].endswith(
        " ms after the request, within the 200 ms timeout: not known whether it was answered")
    assert plugin_fields(path)[2:] == [f"8;1;;;{last['notes'][0]}", "0;;;;"]  # (the closing record: no vw3)


@pytest.mark.parametrize(("suffix", "env"), [("pcap", PURE), ("pcapng", {})], ids=["pcap-python", "pcapng-engine"])
def test_stopped_past_the_timeout(tmp_path: Path, suffix: str, env: dict[str, str]) -> None:
    """Stopped after the timeout: unanswered in every output (the file said 'not known' before)."""
    path = tmp_path / f"past.{suffix}"
    live, err = sniff(path, [(READ, 0.1), (ANSWER, 0.1), (READ, 0.6)], [], env)
    assert "1 unanswered" in err, err
    # Live showed the line when the timeout passed; the file's decode says the same (pairing.capture_ended).
    items = check_one_truth(path, live)
    assert [(item["kind"], item.get("unanswered")) for item in live] == [
        ("request", False), ("response", None), ("request", True)]
    assert items[-1]["unanswered"] is True and live[-1]["notes"] == []
    assert plugin_fields(path)[2].startswith("8;1;;1;")


def test_count_ends_at_the_last_item(tmp_path: Path) -> None:
    """-c 3: the capture ends with its third item (the bytes after it are not written): the closing record
    at that item's time, and its request not known to be answered, live and in the file alike."""
    path = tmp_path / "count.pcap"
    live, err = sniff(path, [(READ, 0.1), (ANSWER, 0.1), (READ, 0.3), (ANSWER, 0.1)], ["-c", "3"], {})
    records = record_times(path)
    assert [length for _, length in records] == [8, 7, 8, 0] and records[-1][0] == records[-2][0], err
    items = check_one_truth(path, live)
    assert items[-1]["notes"] == [UNKNOWN] and items[-1]["unanswered"] is False


def test_adapter_gone_ends_the_capture_at_its_last_read(tmp_path: Path) -> None:
    """The port going away stops the capture: the file ends at the last read as when stopped by hand."""
    path = tmp_path / "gone.pcap"
    live, err = sniff(path, [(READ, 0.1), (ANSWER, 0.1), (READ, 0.6)], [], PURE, vanish=True)
    assert "went away" in err, err
    check_one_truth(path, live)
    assert live[-1]["unanswered"] is True


def test_duration_ends_the_capture_at_its_last_read(tmp_path: Path) -> None:
    """--duration (-a) stops the capture: the file ends at its last read, as when stopped by hand."""
    path = tmp_path / "duration.pcap"
    live, err = sniff(path, [(READ, 0.1), (ANSWER, 0.1), (READ, 1.5)], ["--duration", "0.9"], {})
    assert "1 unanswered" in err, err
    records = record_times(path)
    assert records[-1][0] - records[-2][0] > 200_000  # (the stop: past the last request's timeout)
    check_one_truth(path, live)
