"""CPU a byte of a live capture's reads, fed to the framing as one chunk a read (now) or as a chunk for
each run of bytes with one time (4173324 to 09ae941), in one run.

    python3 bench/live_feed.py [--frames 6000] [--mix plant] [--baud 115200] [--largest 64 | --latency MS] [--repeat 5]

A mix of bench/throughput.py is cut into the reads a USB adapter gives (1..--largest bytes each, stamped
when the last came, a read timing out every 10 ms of silence) and, in this process, fed:

- engine: to the compiled live path (accel/livepath.py LivePath, plain summary), as the display does;
- python: to the capture thread's framer (app/live_capture.py CaptureThread.step, RtuFramer), as
  VW3_PURE_PYTHON=1 does (the pairing and decoding after it are not timed: they do not change);

each three ways: `read` one chunk timing each byte (ReadClock.chunk, runs: now), `runs` a Chunk for each
run (ReadClock.chunks: what 4173324 fed), and `stamp` one chunk at the read's stamp (before 4173324:
every frame at its read's last byte, the wrong times; the floor this work is to come near). The
outputs of `read` and `runs` must be equal, times to the nanosecond. Best of --repeat process-CPU
times, interleaved; us a byte of the stream.

At the commit that made `read` (2026-12-04, this shared 2-core machine at load 5, so the ratios count):
default options: engine read 0.89, runs 2.73 (3.1x), stamp 0.46; python read 0.81, runs 4.00 (5.0x),
stamp 0.45 us/byte. --latency 16: engine 0.57, 2.33 (4.1x), 0.25; python 0.56, 3.86 (6.9x), 0.33.
--baud 921600 --latency 16: engine 0.50, 2.28 (4.6x), 0.23; python 0.51, 3.63 (7.1x), 0.32. The
whole of `vw3-decode --live` replaying a 6,000-frame tape (VW3_LIVE_REPLAY, 19200 baud, start-up
included): engine 0.81 -> 0.54 s CPU, VW3_PURE_PYTHON=1 1.10 -> 0.62 s, the same output.
"""
from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from throughput import MIXES  # noqa: E402

from dissector.accel import livepath  # noqa: E402
from dissector.app.live import live_framer  # noqa: E402
from dissector.app.live_capture import IDLE_FLUSH_LONG, silence_threshold  # noqa: E402
from dissector.model import Chunk, Stamp  # noqa: E402
from dissector.pipeline import Dissector  # noqa: E402
from dissector.render.timefmt import Clock  # noqa: E402
from dissector.sources.serial_times import ReadClock, char_time  # noqa: E402

IDLE_READ = 0.010  # serial_port.READ_TIMEOUT: a read that gives nothing
Read = tuple[bytes, Stamp, float]


def reads_of(records: list[tuple[bytes, float]], baud: int, largest: int, seed: int) -> list[Read]:
    """The reads a port gives of these records (bytes, time of the first byte) at `baud` 8E1."""
    rng = random.Random(seed)
    byte_time = 11 / baud
    start = records[0][1]
    clock = start
    reads: list[Read] = []

    def read(data: bytes, at: float) -> None:
        reads.append((data, Stamp(int(at * 1e6) * 1000), 1000.0 + at - start))

    for data, when in records:
        when = max(when, clock)
        while when - clock > IDLE_READ:
            clock += IDLE_READ
            read(b"", clock)
        at = 0
        while at < len(data):
            piece = data[at : at + rng.randint(1, largest)]
            at += len(piece)
            clock = when + at * byte_time
            read(piece, clock)
    return reads


def burst_reads(records: list[tuple[bytes, float]], baud: int, latency: float) -> list[Read]:
    """The reads of an adapter that gives what came every `latency` seconds (FTDI's latency timer),
    each stamped at the end of its window: a read holds many frames, bytes back-dated to the floor."""
    byte_time = 11 / baud
    start = records[0][1]
    windows: dict[int, bytearray] = {}
    for data, when in records:
        for index, byte in enumerate(data):
            windows.setdefault(int((when - start + (index + 1) * byte_time) / latency), bytearray()).append(byte)
    return [(bytes(windows.get(window, b"")), Stamp(int((start + (window + 1) * latency) * 1e6) * 1000),
             1000.0 + (window + 1) * latency) for window in range(max(windows) + 1)]


def engine(reads: list[Read], baud: int, way: str) -> list[bytes]:
    lines: list[bytes] = []
    dissector = Dissector(live_framer(None, baud))
    path = livepath.LivePath(dissector, None, Clock(), lambda items: None, lines.append, None,
                             silence_threshold(baud), IDLE_FLUSH_LONG, True, None, char_time(baud))
    if way == "runs":
        def add(data: bytes, stamp: Stamp) -> None:
            for chunk in path.clock.chunks(data, stamp):
                for block in path.builder.add(chunk):
                    path.path.feed(block)
        path._add = add  # type: ignore[method-assign]
    elif way == "stamp":
        def add(data: bytes, stamp: Stamp) -> None:
            for block in path.builder.add(Chunk(data, time=stamp)):
                path.path.feed(block)
        path._add = add  # type: ignore[method-assign]
    for read in reads:
        path.feed([read])
    path.finish()
    return lines


def python(reads: list[Read], baud: int, way: str) -> list[tuple[object, ...]]:
    framer = live_framer(None, baud)
    clock = ReadClock(char_time(baud))
    items = []
    for data, stamp, _now in reads:
        if way == "read":
            chunk = clock.chunk(data, stamp)
            if chunk is not None:
                items += framer.feed(chunk)
        elif way == "runs":
            for chunk in clock.chunks(data, stamp):
                items += framer.feed(chunk)
        elif data:
            items += framer.feed(Chunk(data, time=stamp))
    items += framer.finish()
    return [(type(item).__name__, item.offset, item.length, item.time.ns) for item in items]  # type: ignore[union-attr]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=6000)
    parser.add_argument("--mix", default="plant", choices=[mix.name for mix in MIXES])
    parser.add_argument("--baud", type=int, default=115200)
    parser.add_argument("--largest", type=int, default=64, help="the longest read, bytes")
    parser.add_argument("--latency", type=float, default=0.0,
                        help="ms: reads of all that came in each such window instead (an FTDI adapter: 16)")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    mix = next(mix for mix in MIXES if mix.name == args.mix)
    if args.latency:
        reads = burst_reads(mix.records(args.frames), args.baud, args.latency / 1000)
        how = f"a read every {args.latency:g} ms"
    else:
        reads = reads_of(mix.records(args.frames), args.baud, args.largest, 1)
        how = f"reads of 1..{args.largest} bytes"
    size = sum(len(data) for data, _stamp, _now in reads)
    print(f"{mix.name}: {args.frames:,} frames, {size:,} bytes in {sum(1 for read in reads if read[0]):,} reads "
          f"({how}) at {args.baud} baud, best of {args.repeat}")
    if not livepath.available():
        print("(no engine: python only)")
    sides = {"engine": engine, "python": python} if livepath.available() else {"python": python}
    best: dict[tuple[str, str], float] = {}
    outputs: dict[tuple[str, str], object] = {}
    for _round in range(args.repeat):
        for side, run in sides.items():
            for way in ("read", "runs", "stamp"):
                started = time.process_time()
                output = run(reads, args.baud, way)
                seconds = time.process_time() - started
                best[side, way] = min(best.get((side, way), seconds), seconds)
                outputs.setdefault((side, way), output)
    same = all(outputs[side, "read"] == outputs[side, "runs"] for side in sides)
    for side in sides:
        figures = {way: best[side, way] / size * 1e6 for way in ("read", "runs", "stamp")}
        print(f"  {side:6}: read {figures['read']:.2f} us/byte, runs {figures['runs']:.2f} us/byte "
              f"({figures['runs'] / figures['read']:.1f}x), stamp {figures['stamp']:.2f} us/byte")
    print(f"read and runs equal, times to the ns: {'yes' if same else 'NO'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
