"""A differential campaign of the engine's noise framing (dissector/accel/_noise.h, fastsummary.skip_noise)
against the Python stages, for as long as asked.

    python3 bench/noise_span_fuzz.py [SECONDS] [SEED]

Each round makes a noisy stream from a random recipe (random bytes; frame starts, glitch bytes, scanned codes
and the awaited answer's slave and function salted through them; valid traffic, requests awaiting answers and
FC8 echoes before, between and after; a line learnt glitchy) and decodes it with `vw3-decode` in-process, with
the engine and with VW3_PURE_PYTHON=1: raw, in a summary or --stats, and as a pcap of records of 1..8, 20..60
or 200 bytes, with or without silences between some. Any difference is printed with the recipe's seed and
the run stops (exit 1).
"""
from __future__ import annotations

import random
import struct
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "bench")]

from dissector.protocol.crc import with_crc  # noqa: E402
from dissector.sim.simulate import generate_session  # noqa: E402
from timed_fuzz import decode  # noqa: E402  (the engine's and the Python stages' outputs, as the timed campaign)

STARTS = (b"\x0c\x03", b"\x0c\x83", b"\x0c\x08\x00\x00", b"\x0c\x08", b"\x01\x03", b"\x01\x10", b"\x00", b"\xff",
          b"\xfe", b"\x00\x03", b"\x00\x06", b"\xf8\x03", b"\x01\x2b\x0e", b"\x01\x2b\x0e\x01\x01\x00\x00\x02",
          b"\x07\x41", b"\x11\x11", b"\x05\x17")
AWAITING = (with_crc(bytes.fromhex("0c0320d00003")), with_crc(bytes.fromhex("0c0800001234")),
            with_crc(bytes.fromhex("01030000000a")), with_crc(bytes.fromhex("0c0800010000")))


def noise(rng: random.Random, size: int) -> bytes:
    salt = rng.sample(STARTS, rng.randint(0, 5))
    out = bytearray()
    while len(out) < size:
        if salt and rng.random() < 0.5:
            out += rng.choice(salt)
        out += rng.randbytes(rng.randint(0, 30))
    return bytes(out[:size])


def stream(rng: random.Random) -> bytes:
    frames = [data for data, _time in generate_session(rng.randint(5, 60), seed=rng.randrange(1000))]
    glitchy = rng.random() < 0.3
    parts = []
    for _ in range(rng.randint(1, 4)):
        take = rng.randint(0, len(frames))
        parts += [frame + (b"\x00" if glitchy else b"") for frame in frames[:take]]
        frames = frames[take:]
        if rng.random() < 0.6:
            parts.append(rng.choice(AWAITING))
        parts.append(noise(rng, rng.randint(1, 6000)))
    parts += frames
    return b"".join(parts)


def as_pcap(rng: random.Random, data: bytes) -> bytes:
    low, high = rng.choice([(1, 8), (20, 60), (200, 200)])
    gap = rng.choice([0, 0, 3_000_000])
    out = bytearray(struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147))
    ns, start = 1_700_000_000 * 10**9, 0
    while start < len(data):
        record = data[start : start + rng.randint(low, high)]
        out += struct.pack("<IIII", ns // 10**9, ns % 10**9, len(record), len(record)) + record
        ns += len(record) * 573_000 + (gap if rng.random() < 0.3 else 0)
        start += len(record)
    return bytes(out)


def main() -> int:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    end = time.monotonic() + seconds
    rounds = 0
    with tempfile.TemporaryDirectory() as folder:
        while time.monotonic() < end:
            rng = random.Random(seed * 1_000_003 + rounds)
            data = stream(rng)
            pcap = rng.random() < 0.5
            path = Path(folder) / ("bus.pcap" if pcap else "bus.bin")
            path.write_bytes(as_pcap(rng, data) if pcap else data)
            argv = [str(path)] + (["--stats"] if rng.random() < 0.2 else [])
            if decode(argv, False) != decode(argv, True):
                print(f"round {rounds} (seed {seed}): outputs differ, {'pcap' if pcap else 'raw'} {argv[1:]}")
                return 1
            rounds += 1
    print(f"{rounds} rounds, no difference")
    return 0


if __name__ == "__main__":
    sys.exit(main())
