"""Tapes of live reads (dissector/app/live_capture.py Tape) made from simulated traffic, for the
differential tests of the compiled live path: a bus's frames (dissector/sim) as a USB adapter delivers
them (random reads of 1..64 bytes, each stamped when its last byte came), with the port's idle reads
(every 10 ms of silence, as serial_port.READ_TIMEOUT), and damage: bytes flipped, glitch bytes, noise
runs, a slave that answers after the timeout or not at all."""
from __future__ import annotations

import os
import random
import subprocess
import sys
from pathlib import Path

from dissector.app.live_capture import _TAPE_EVENT
from dissector.sim.simulate import Record

IDLE_READ = 0.010  # a read that times out: the port's READ_TIMEOUT
ROOT = Path(__file__).resolve().parents[2]


def run_cli(argv: list[str], pure: bool, tape: Path | None = None) -> subprocess.CompletedProcess[str]:
    """vw3-decode in a process of its own, on the compiled path or the Python stages (`pure`); with a tape,
    as `--live` on a port that replays it (VW3_LIVE_REPLAY)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    if tape is not None:
        env["VW3_LIVE_REPLAY"] = str(tape)
        argv = ["--live", "/dev/ttyTAPE", "--baud", "19200", *argv]
    return subprocess.run([sys.executable, "-m", "dissector", *argv], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=300)


def damaged(records: list[Record], rng: random.Random, rate: float = 0.02) -> list[Record]:
    """Records with a byte flipped, glitch bytes after them, noise between them, or dropped (an
    answer that never came), each at about `rate`."""
    out: list[Record] = []
    shift = 0.0  # a slave that answered late delays the rest of the bus
    for data, when in records:
        when += shift
        roll = rng.random()
        if roll < rate:
            index = rng.randrange(len(data))
            data = data[:index] + bytes([data[index] ^ (1 << rng.randrange(8))]) + data[index + 1 :]
        elif roll < 2 * rate:
            data = data + rng.choice([b"\x00", b"\xfe", b"\xff\xff", b"\x80"])
        elif roll < 3 * rate:
            out.append((bytes(rng.randrange(256) for _ in range(rng.randint(1, 40))), when - 0.004))
        elif roll < 3.5 * rate:
            continue  # lost on the line
        elif roll < 4 * rate:
            delay = rng.choice([0.3, 1.2, 2.5])  # a long silence; later than the --timeout of 1 s: late
            when += delay
            shift += delay
        out.append((data, when))
    out.sort(key=lambda record: record[1])
    return out


def tape_of(records: list[Record], rng: random.Random, baud: int = 19200, largest: int = 64) -> bytes:
    """The reads a live capture makes of these records (bytes, time of their first byte), each of 1 to
    `largest` bytes."""
    byte_time = 11 / baud
    events: list[tuple[bytes, int, float]] = []
    start_ns = int(records[0][1] * 1e9) // 1000 * 1000
    start_mono = 1000.0
    clock = records[0][1]
    for data, when in records:
        when = max(when, clock)
        while when - clock > IDLE_READ:  # the port's reads time out while the line is silent
            clock += IDLE_READ
            events.append((b"", _ns(clock), start_mono + clock - records[0][1]))
        at = 0
        while at < len(data):
            size = rng.randint(1, largest)
            piece = data[at : at + size]
            at += len(piece)
            clock = when + at * byte_time + rng.random() * 0.0005
            events.append((piece, _ns(clock), start_mono + clock - records[0][1]))
    for _ in range(40):  # then the line stays silent: every flush happens
        clock += IDLE_READ
        events.append((b"", _ns(clock), start_mono + clock - records[0][1]))
    del start_ns
    return b"".join(_TAPE_EVENT.pack(mono, ns, len(data)) + data for data, ns, mono in events)


def _ns(seconds: float) -> int:
    return int(seconds * 1e6) * 1000  # stamped to the microsecond, as stamp_now


def write_tape(path: Path, records: list[Record], seed: int, damage: float = 0.0, largest: int = 64) -> Path:
    rng = random.Random(seed)
    if damage:
        records = damaged(records, rng, damage)
    path.write_bytes(tape_of(records, rng, largest=largest))
    return path
