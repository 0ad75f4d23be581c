"""A -w copy of a nanosecond capture keeps its nanoseconds (app/inputs.py write_units: a nanosecond pcap,
a pcapng interface with if_tsresol finer than microseconds), as tshark -w and editcap keep them: COPY
decodes as FILE does, the time column, --json's times and response times, and the plugin's.

Before, every copy was written in microseconds: the time column said 0.010000 where FILE said 0.010001
(10 000 700 ns), --json's response_time 0.004583 where FILE's was 0.004583876, the plugin's
vw3.response_time the same. A microsecond capture is copied in microseconds, as before.
"""
from __future__ import annotations

import json
import os
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from live_bus import ROOT
from lua_harness import lua_errors, run_tshark

pytestmark = pytest.mark.integration
REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("010304000100022A32")
SECONDS = 1_767_225_600
RECORDS = [(REQUEST, 0), (ANSWER, 10_000_700), (REQUEST, 1_000_000_123), (ANSWER, 1_004_583_999)]  # ns
LINES = [  # (nanoseconds: 9 decimals, as tshark's column)
    "     1  0.000000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     2  0.010000700   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok",
    "     3  1.000000123   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     4  1.004583999   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#3, 4.6 ms]  CRC ok",
]
TIMES = [(1767225600.0, None), (1767225600.0100007, 0.0100007), (1767225601.0000002, None),
         (1767225601.004584, 0.004583876)]
PLUGIN = ["0.000000000;", "0.010000700;0.010000700", "1.000000123;", "1.004583999;0.004583876"]
NANO_MAGIC, MICRO_MAGIC = bytes.fromhex("4d3cb2a1"), bytes.fromhex("d4c3b2a1")


def nanosecond_pcap(path: Path) -> Path:
    records = b"".join(struct.pack("<IIII", SECONDS + ns // 10**9, ns % 10**9, len(data), len(data)) + data
                       for data, ns in RECORDS)
    path.write_bytes(struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147) + records)
    return path


def run(*arguments: object, stdin: bytes | None = None) -> list[str]:
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", *map(str, arguments)], cwd=ROOT,
                          env=dict(os.environ), input=stdin, capture_output=True, timeout=120)
    assert done.returncode == 0 and not done.stderr, done.stderr
    return done.stdout.decode().splitlines()


def times(path: Path) -> list[tuple[float, float | None]]:
    return [(item["time"], item.get("response_time")) for item in map(json.loads, run(path, "--json"))]


def plugin(path: Path) -> list[str]:
    result = run_tshark(path, "-T", "fields", "-E", "separator=;", "-e", "frame.time_relative",
                        "-e", "vw3.response_time")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("copy", ["pcap", "pcapng"])
def test_a_nanosecond_capture_is_copied_in_nanoseconds(tmp_path: Path, copy: str) -> None:
    original = nanosecond_pcap(tmp_path / "ns.pcap")
    assert run(original) == LINES
    assert times(original) == TIMES
    written = tmp_path / f"copy.{copy}"
    run(original, "-w", written)
    assert run(written) == LINES  # was 0.010000 and 1.004583
    assert times(written) == TIMES  # was (1767225600.01, 0.01), (1767225601.004583, 0.004583)
    assert plugin(written) == plugin(original) == PLUGIN
    if copy == "pcap":
        assert written.read_bytes()[:4] == NANO_MAGIC
    # A copy of the copy (a pcapng interface in nanoseconds, if_tsresol 9) keeps them too.
    again = tmp_path / "again.pcap"
    run(written, "-w", again)
    assert again.read_bytes()[:4] == NANO_MAGIC and run(again) == LINES


@pytest.mark.parametrize("source", ["pcap", "pcapng"])
def test_standard_input_is_judged_by_its_head(tmp_path: Path, source: str) -> None:
    """`tshark -w - | vw3-decode - -w COPY`: the pcap's magic, or the pcapng's first interface blocks,
    peeked at before the input is read (app/inputs.py write_units)."""
    original = nanosecond_pcap(tmp_path / "ns.pcap")
    if source == "pcapng":
        run(original, "-w", tmp_path / "ns.pcapng")
        original = tmp_path / "ns.pcapng"
    written = tmp_path / "copy.pcap"
    run("-", "-w", written, stdin=original.read_bytes())
    assert written.read_bytes()[:4] == NANO_MAGIC and run(written) == LINES  # was 0.010000 and 1.004583


def _block(block_type: int, body: bytes) -> bytes:
    body += bytes(-len(body) % 4)
    return struct.pack("<II", block_type, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def test_binary_units_are_copied_in_nanoseconds(tmp_path: Path) -> None:
    """A pcapng interface in 1/1024 s (if_tsresol 0x8A): read to the nanosecond, which microseconds
    cannot hold (1025/1024 s is 1.000976562 s: the time column's 1.000977 was 1.000976 in the copy)."""
    section = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    tsresol = struct.pack("<HHB3x", 9, 1, 0x8A) + struct.pack("<HH", 0, 0)
    interface = _block(1, struct.pack("<HHI", 147, 0, 65535) + tsresol)
    start = SECONDS * 1024
    packets = b"".join(
        _block(6, struct.pack("<IIIII", 0, ticks >> 32, ticks & 0xFFFFFFFF, len(data), len(data)) + data)
        for ticks, data in [(start, REQUEST), (start + 11, ANSWER), (start + 1025, ANSWER)])
    original = tmp_path / "binary.pcapng"
    original.write_bytes(section + interface + packets)
    lines = run(original)
    assert [line.split()[1] for line in lines] == ["0.000", "0.010", "1.000"]  # (ms, cut: as tshark's column)
    written = tmp_path / "copy.pcap"
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", str(original), "-w", str(written)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    # (pcap holds microseconds or nanoseconds: a pcapng copy keeps 2^-10 s, test_copy_tsresol.py)
    assert done.returncode == 0 and "cannot hold the time resolution" in done.stderr
    copied = run(written)  # was 1.000976 (then 6 decimals)
    assert written.read_bytes()[:4] == NANO_MAGIC
    assert [line.split()[1] for line in copied] == ["0.000000000", "0.010742187", "1.000976562"]
    assert [line.split()[2:] for line in copied] == [line.split()[2:] for line in lines]


def test_a_text_log_with_nanoseconds(tmp_path: Path) -> None:
    """A hex dump whose times have nanoseconds (`date +%s.%N`): its copy in nanoseconds (was 0.010000)."""
    dump = tmp_path / "ns.txt"
    lines = [f"{SECONDS + ns // 10**9}.{ns % 10**9:09d} {data.hex(' ')}\n" for data, ns in RECORDS]
    dump.write_text("".join(lines))
    assert run(dump) == LINES
    written = tmp_path / "copy.pcap"
    run(dump, "-w", written)
    assert written.read_bytes()[:4] == NANO_MAGIC and run(written) == LINES


def test_a_microsecond_capture_stays_in_microseconds(tmp_path: Path) -> None:
    original = tmp_path / "us.pcap"
    run(nanosecond_pcap(tmp_path / "ns.pcap"), "-w", tmp_path / "first.pcap")
    path = tmp_path / "first.pcap"
    data = bytearray(path.read_bytes())
    data[:4] = MICRO_MAGIC  # the same records in a microsecond pcap: their fractions rounded down
    position = 24
    while position < len(data):
        seconds, fraction, length, _ = struct.unpack_from("<IIII", data, position)
        struct.pack_into("<I", data, position + 4, fraction // 1000)
        position += 16 + length
    original.write_bytes(bytes(data))
    written = tmp_path / "copy.pcap"
    run(original, "-w", written)
    assert written.read_bytes() == original.read_bytes()
