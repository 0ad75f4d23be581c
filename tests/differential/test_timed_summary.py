"""The compiled path for timed captures (dissector/accel/timedpath.py; the engine's run_timed in
dissector/accel/_summary.c) against the Python stages (VW3_PURE_PYTHON=1), the reference: the same
summary lines byte for byte, on pcap and pcapng files whose records cut the stream at random (one frame
a record, several, frames split across records), with times (response times, the time column, silences
inside frames and between them, late answers past the timeout, untimed records) and damage. The
extension must be built: it is not skipped.
"""
from __future__ import annotations

import io
import random
import struct
import sys
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.output import Output
from dissector.render.pcapngwriter import PcapngWriter
from dissector.sim.simulate import generate_session

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import noise_accuracy  # noqa: E402

CHAR_NS = 11 * 1_000_000_000 // 19200  # one character at 19200 baud


def write_pcap(path: Path, records: list[tuple[bytes, int | None]], nano: bool = True) -> None:
    """A classic pcap (linktype 147): each record's bytes at its time in ns (None: untimed, time 0)."""
    units = 1_000_000_000 if nano else 1_000_000
    magic = 0xA1B23C4D if nano else 0xA1B2C3D4
    with path.open("wb") as out:
        out.write(struct.pack("<IHHiIII", magic, 2, 4, 0, 0, 65535, 147))
        for data, ns in records:
            seconds, fraction = divmod(ns or 0, 1_000_000_000)
            out.write(struct.pack("<IIII", seconds, fraction * units // 1_000_000_000, len(data), len(data)) + data)


def write_pcapng(path: Path, records: list[tuple[bytes, int | None]]) -> None:
    with path.open("wb") as out:
        writer = PcapngWriter(out, flush=False)
        for data, ns in records:
            writer.write(data, None if ns is None else ns / 1e9)


def frames_of(seed: int, damaged: float) -> list[tuple[bytes, int]]:
    """Frames of a random bus with their start times in ns: answers after 2..60 ms, some damaged."""
    rng = random.Random(seed)
    frames = noise_accuracy.session(rng, 300)
    timed = []
    ns = 1_700_000_000 * 1_000_000_000 + rng.randrange(10**9)
    for frame in frames:
        if rng.random() < damaged:
            _how, frame = noise_accuracy.damage(rng, frame)
        timed.append((frame, ns))
        ns += len(frame) * CHAR_NS + rng.choice([1_000_000, 2_000_000, 5_000_000, 40_000_000, 1_500_000_000])
    return timed


def cut_records(rng: random.Random, frames: list[tuple[bytes, int]], how: str) -> list[tuple[bytes, int | None]]:
    """Records as sniffers write them: one frame each, or the stream cut anywhere (USB latency
    bursts), a byte's time by its place in its frame, some bursts late inside a frame."""
    if how == "frame":
        return [(frame, ns) for frame, ns in frames]
    stream = bytearray()
    times: list[int] = []
    for frame, ns in frames:
        stream += frame
        times += [ns + k * CHAR_NS for k in range(len(frame))]
    records: list[tuple[bytes, int | None]] = []
    start = 0
    while start < len(stream):
        end = min(len(stream), start + rng.choice([1, 2, 3, 5, 8, 13, 16, 40, 64]))
        ns: int | None = times[start] + rng.choice([0, 0, 0, 300_000, 2_000_000])
        if how == "untimed" and rng.random() < 0.3:
            ns = None
        records.append((bytes(stream[start:end]), ns))
        start = end
    return records


def decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool, stdin: bytes = b"") -> tuple[str, int]:
    """The output, and how many lines the engine wrote itself."""
    if pure:
        monkeypatch.setenv("VW3_PURE_PYTHON", "1")
    else:
        monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    engine_lines = 0
    write_encoded = Output.write_encoded

    def counting(self: Output, lines: bytes) -> None:
        nonlocal engine_lines
        engine_lines += lines.count(b"\n")
        write_encoded(self, lines)

    monkeypatch.setattr(Output, "write_encoded", counting)
    stdout, stderr = io.StringIO(), io.StringIO()
    env = Environment(io.BytesIO(stdin), stdout, stderr, False, False)
    assert run(argv, env) == 0
    return stdout.getvalue() + stderr.getvalue(), engine_lines  # (warnings: the reader's, both ways)


def assert_same(argv: list[str], monkeypatch: pytest.MonkeyPatch, stdin: bytes = b"") -> tuple[str, int]:
    fast, engine_lines = decode(argv, monkeypatch, pure=False, stdin=stdin)
    reference, none = decode(argv, monkeypatch, pure=True, stdin=stdin)
    assert none == 0
    assert fast == reference
    return fast, engine_lines


def same_lines_of_records(tmp_path: Path, records: list[tuple[bytes, float]],
                          monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The summary lines of a pcap of `records` (bytes, seconds after 1700000000 s), the engine's equal to the
    Python stages' there and under -V, --json and -x."""
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, [(data, 1_700_000_000 * 10**9 + round(time * 1e9)) for data, time in records])
    out, _ = assert_same([str(capture)], monkeypatch)
    for option in (["-V"], ["--json"], ["-x"]):
        assert_same([str(capture), *option], monkeypatch)
    return out.splitlines()


OPTIONS = [[], ["-n"], ["-t", "d"], ["-t", "dd"], ["--timeout", "0.03"], ["--baud", "9600"], ["--profile", "atv71"]]


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("how", ["frame", "bursts", "untimed"])
def test_random_records_same_lines(seed: int, how: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed * 7 + len(how))
    frames = frames_of(seed, damaged=0.0 if seed % 3 == 0 else 0.08)
    records = cut_records(rng, frames, how)
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, records, nano=seed % 2 == 0)
    for options in OPTIONS[seed % 3 :: 3] + [OPTIONS[0]]:
        assert_same([str(capture), *options], monkeypatch)


@pytest.mark.parametrize("seed", range(3))
def test_pcapng_same_lines(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    records = cut_records(rng, frames_of(seed + 10, damaged=0.05), "frame" if seed == 0 else "bursts")
    capture = tmp_path / "bus.pcapng"
    write_pcapng(capture, records)
    assert_same([str(capture)], monkeypatch)
    assert_same([str(capture), "-t", "d", "--timeout", "0.01"], monkeypatch)


def test_clean_polling_pcap_comes_from_the_engine(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A sniffer's pcap of a healthy bus: one frame a record, nearly every line from the engine, with
    its time column and response times."""
    records = generate_session(1500, seed=3)
    capture = tmp_path / "polling.pcap"
    write_pcap(capture, [(data, round(time * 1e9)) for data, time in records], nano=False)
    fast, engine_lines = assert_same([str(capture)], monkeypatch)
    lines = fast.splitlines()
    assert engine_lines > 0.85 * len(lines)
    assert lines[0].startswith("     1     0.000000 ")
    assert any(" ms]  CRC ok" in line for line in lines)
    assert_same([str(capture), "-t", "dd", "--profile", "atv71"], monkeypatch)
    # Read once from standard input: profile auto chooses as it goes ([provisional] until then).
    piped, engine_lines = assert_same(["-"], monkeypatch, stdin=capture.read_bytes())
    assert engine_lines > 0.5 * len(piped.splitlines())


def test_late_answers_and_silences_inside_frames(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A response past the timeout, and a request whose bytes stop for 20 ms: the Python stages' warnings."""
    from helpers import rtu

    read = rtu("01 03 0000 0002")
    answer = rtu("01 03 04 0001 0002")
    base = 1_700_000_000 * 10**9
    records = [
        (read, base), (answer, base + 10_000_000),                      # answered in 10 ms
        (read, base + 100_000_000), (answer, base + 1_300_000_000),     # 1.2 s later: past the 1 s timeout
        (read[:3], base + 2_000_000_000), (read[3:], base + 2_020_000_000),  # a silence inside the request
        (answer, base + 2_040_000_000),
    ]
    capture = tmp_path / "late.pcap"
    write_pcap(capture, records)
    fast, _engine_lines = assert_same([str(capture)], monkeypatch)
    assert "later than the 1000 ms timeout" in fast
    assert "silence of" in fast
    assert "[#1, 10.0 ms]" in fast


def raw_pcap(path: Path, records: list[tuple[int, int, int, bytes]], big_endian: bool = False) -> None:
    """A pcap from (seconds, microseconds, original length, captured bytes) records, as written."""
    order = ">" if big_endian else "<"
    with path.open("wb") as out:
        out.write(struct.pack(order + "IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147))
        for seconds, micros, original, data in records:
            out.write(struct.pack(order + "IIII", seconds, micros, len(data), original) + data)


@pytest.mark.parametrize("read_bytes", [37, 1 << 20])
@pytest.mark.parametrize("big_endian", [False, True])
def test_odd_pcap_records_read_in_bulk_as_the_reader_does(read_bytes: int, big_endian: bool, tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """Records the bulk reader leaves to sources/pcap.py (captured in part, longer than a chunk, cut by the
    end of the file) and those it reads itself (empty, untimed, across its reads): same lines, same warnings."""
    from dissector.accel import records as bulk
    from helpers import rtu

    monkeypatch.setattr(bulk, "READ_BYTES", read_bytes)
    read, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    records = []
    for k in range(40):
        records += [(1_700_000_000 + k, 1000, len(read), read), (1_700_000_000 + k, 9000, len(answer), answer)]
    records[7:7] = [(1_700_000_000, 5000, 0, b""), (0, 0, len(read), read)]  # empty; untimed (time 0)
    records[30:30] = [(1_700_000_010, 0, 64, read)]  # captured in part
    records.append((1_700_000_050, 0, 70000, bytes(70000)))  # longer than a chunk: split by the reader
    records += [(1_700_000_051, 0, len(read), read)] * 3
    capture = tmp_path / "odd.pcap"
    raw_pcap(capture, records, big_endian)
    whole = capture.read_bytes()
    fast, engine_lines = assert_same([str(capture)], monkeypatch)
    assert engine_lines > 40
    assert "only 8 of its 64 bytes were captured" in fast
    (tmp_path / "cut.pcap").write_bytes(whole[:-5])  # the last record cut short
    assert "is cut short" in assert_same([str(tmp_path / "cut.pcap")], monkeypatch)[0]
    (tmp_path / "head.pcap").write_bytes(whole[: 24 + 16 + len(read) + 7])  # a header cut short
    assert_same([str(tmp_path / "head.pcap")], monkeypatch)


def test_times_far_apart_same_lines(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Times months apart (their differences in ns do not fit a double exactly): the engine rounds them
    once, as the Python stages do, wherever it hands over and takes back."""
    from helpers import rtu

    read, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    records: list[tuple[bytes, int | None]] = []
    for k in range(30):
        base = 1_000_000_000 * 10**9 + k * 200 * 86_400 * 10**9 + 123_456_789
        records += [(read, base), (answer, base + 10_123_457)]
    capture = tmp_path / "far.pcap"
    write_pcap(capture, records)
    for options in ([], ["-t", "d"], ["-t", "dd"]):
        assert_same([str(capture), *options], monkeypatch)


@pytest.mark.parametrize("seed", range(3))
def test_hex_dumps_same_lines(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Text hex dumps, a line a read, with times in seconds, ISO date-times, or none; damaged."""
    rng = random.Random(seed)
    records = cut_records(rng, frames_of(seed + 60, damaged=0.05), ["frame", "bursts", "untimed"][seed])
    lines = []
    for data, ns in records:
        if ns is None or seed == 2:
            stamp = ""
        elif seed == 0:
            stamp = f"{ns // 10**9}.{ns % 10**9 // 1000:06d} "
        else:
            seconds, fraction = divmod(ns, 10**9)
            from datetime import datetime, timezone

            stamp = datetime.fromtimestamp(seconds, timezone.utc).strftime("%Y-%m-%dT%H:%M:%S") + f".{fraction // 1000:06d} "
        lines.append(stamp + data.hex(" "))
    dump = tmp_path / "bus.txt"
    dump.write_text("\n".join(lines) + "\n")
    for options in ([], ["--json"], ["-t", "d"]):
        assert_same([str(dump), *options], monkeypatch)


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_a_pipe_is_never_held_back(suffix: str, tmp_path: Path) -> None:
    """From a pipe (a capture still being written), the records there are handed on as they come, not
    when a block's worth has arrived: all of them while the writer still holds the pipe open."""
    import os
    import threading

    from dissector.accel.records import blocks_from_chunks
    from dissector.framing.timing import LineTiming
    from dissector.sources.reader import open_source
    from helpers import rtu

    read, answer = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
    capture = tmp_path / f"two.{suffix}"
    (write_pcap if suffix == "pcap" else write_pcapng)(capture, [(read, 10**18), (answer, 10**18 + 10**7)] * 40)
    reading, writing = os.pipe()
    os.write(writing, capture.read_bytes())  # (the writer keeps the pipe open: no end of input)
    got: list = []

    def blocks() -> None:
        with os.fdopen(reading, "rb") as stream:
            for block in blocks_from_chunks(open_source("-", stdin=stream), LineTiming()):
                got.extend(block.starts)

    thread = threading.Thread(target=blocks, daemon=True)
    thread.start()
    thread.join(5)
    received = len(got)
    os.close(writing)
    thread.join(10)
    assert received == len(got) == 80
