"""The compiled engine against the Python stages on noisy and damaged raw streams, one run.

    python3 bench/noise_throughput.py [--bytes 500000] [--repeat 2] [--kind NAME] [--instructions]
                                      [--option=--stats]

The engine hands noise and damaged frames to the Python stages (dissector/accel/fastsummary.py), so on
such a stream it can be no faster than they are; this bench holds it to that, on the same files in one
run, beside a clean stream of the same size for the engine's own speed. Kinds (each reproducible):
- random: random bytes (a line read at the wrong baud rate, the worst case of the framer);
- random-reads: the same bytes as a pcap of one-byte records (a USB tap's reads; --bytes 20000 is enough);
- zeros: 00 bytes (a line held low), which no frame can start: skipped by a regular expression;
- bad-crc: one FC16 request of 20 registers with a bad CRC, repeated (a damaged line, every frame);
- garbage: the plant mix (dissector.sim.mixes.plant_mix) with 1..16 random bytes after a fifth of its
  frames;
- glitches: the plant mix with a turn-around glitch byte on both sides of half its frames
  (dissector.sim.line, `glitches both sides`);
- plant: the plant mix as it is (no noise): the engine's speed on valid traffic;
- stuck-0c, stuck-01, babble-0103: a line stuck on one value (0C: FC12, whose request and answer both
  fit everywhere; 01) or a device babbling 01 03 (hostile traffic: every position may start a frame, each
  weighed in full before framing/rtu.py _repeats).
For each kind and each side (the engine; VW3_PURE_PYTHON=1) it takes the CPU seconds (user + system) of
`python3 -m dissector FILE` (plus --option), best of --repeat interleaved rounds, checks that both
outputs are the same bytes, and prints the ratio (above 1: the engine is faster). With --instructions
it counts machine instructions instead (valgrind's callgrind, one run each; a shared machine's load
does not move them). The package is byte-compiled first, as pip does.
"""
from __future__ import annotations

import argparse
import os
import random
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from dissector.protocol.crc import with_crc  # noqa: E402
from dissector.sim.line import on_the_line  # noqa: E402
from dissector.sim.mixes import PLANT_PROFILES, plant_mix  # noqa: E402

VW3 = [sys.executable, "-m", "dissector"]
PLANT_OPTIONS = [option for profile in PLANT_PROFILES for option in ("--profile", profile)]


def _plant_frames(size: int) -> list[bytes]:
    frames: list[bytes] = []
    total = 0
    count = max(100, size // 20)
    for data, _time in plant_mix(count, seed=1):
        frames.append(data)
        total += len(data)
        if total >= size:
            break
    return frames


def random_bytes(size: int) -> bytes:
    return random.Random(44).randbytes(size)


def random_reads(size: int) -> bytes:
    """random_bytes as a pcap of one-byte records 1 ms apart: a USB tap's reads of a line at the wrong speed, each
    record end a boundary the framer weighs (framing/offsets.py)."""
    header = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    return header + b"".join(struct.pack("<IIII", 1_700_000_000 + index // 1000, index % 1000 * 1000, 1, 1)
                             + bytes([byte]) for index, byte in enumerate(random_bytes(size)))


def zeros(size: int) -> bytes:
    return bytes(size)


def bad_crc(size: int) -> bytes:
    frame = bytearray(with_crc(bytes([1, 0x10, 0x00, 0x64, 0x00, 20, 40]) + bytes(range(40))))
    frame[-1] ^= 0x5A
    return bytes(frame) * (size // len(frame) + 1)


def garbage(size: int) -> bytes:
    rng = random.Random(45)
    stream = bytearray()
    for frame in _plant_frames(size):
        stream += frame
        if rng.random() < 0.2:
            stream += rng.randbytes(rng.randint(1, 16))
    return bytes(stream)


def glitches(size: int) -> bytes:
    frames = _plant_frames(size)
    # (which frames are requests matters to `glitch after` alone)
    return on_the_line(frames, [True] * len(frames), "glitches both sides", random.Random(46)).stream


def plant(size: int) -> bytes:
    return b"".join(_plant_frames(size))


def repeated(pattern: bytes):
    return lambda size: pattern * (size // len(pattern))


KINDS = {
    "random": (random_bytes, []),
    "random-reads": (random_reads, []),
    "zeros": (zeros, []),
    "bad-crc": (bad_crc, []),
    "garbage": (garbage, PLANT_OPTIONS),
    "glitches": (glitches, PLANT_OPTIONS),
    "plant": (plant, PLANT_OPTIONS),
    "stuck-0c": (repeated(b"\x0c"), []),
    "stuck-01": (repeated(b"\x01"), []),
    "babble-0103": (repeated(b"\x01\x03"), []),
}

# Runs a command and prints the CPU seconds (user + system) of it and its children.
PROBE = """
import os, resource, subprocess, sys
with open(sys.argv[1], "wb") as sink:
    result = subprocess.run(sys.argv[2:], stdout=sink, stderr=subprocess.DEVNULL)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(result.returncode, usage.ru_utime + usage.ru_stime)
"""


def environment(pure: bool) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    return env


def cpu_seconds(command: list[str], output: Path, pure: bool) -> float:
    probe = subprocess.run([sys.executable, "-c", PROBE, str(output), *command], env=environment(pure),
                           capture_output=True, text=True, check=True)
    code, seconds = probe.stdout.split()
    if code not in ("0", "1"):  # (1: a warning, e.g. no valid frame in the input)
        sys.exit(f"{' '.join(command)} exited {code}")
    return float(seconds)


def instructions(command: list[str], pure: bool) -> int:
    probe = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", *command],
                           env=environment(pure), capture_output=True, text=True)
    for line in probe.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split()[-1])
    sys.exit(f"no callgrind total for {' '.join(command)}:\n{probe.stderr[-2000:]}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bytes", type=int, default=500_000, help="size of each stream")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--kind", action="append", choices=list(KINDS), help="only these kinds")
    parser.add_argument("--option", action="append", default=[], help="a vw3-decode option (--option=--stats)")
    parser.add_argument("--instructions", action="store_true", help="callgrind instruction counts, one run each")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "dissector")], check=True)
    chosen = [name for name in KINDS if not args.kind or name in args.kind]
    commands = {}
    for name in chosen:
        make, options = KINDS[name]
        path = args.out / f"noise-{name}.bin"
        path.write_bytes(make(args.bytes))
        commands[name] = VW3 + [str(path), *options, *args.option]
    unit = "instructions" if args.instructions else "CPU s"
    print(f"{' '.join(args.option) or 'summary'}, {args.bytes:,} bytes a stream, {unit}")
    print(f"| kind | engine | VW3_PURE_PYTHON=1 | engine vs pure |")
    print("|---|---:|---:|---:|")
    for name in chosen:
        command = commands[name]
        outputs = {pure: args.out / f"noise-{name}{'-pure' if pure else ''}.txt" for pure in (False, True)}
        if args.instructions:
            best = {pure: float(instructions(command, pure)) for pure in (False, True)}
            subprocess.run([sys.executable, "-c", PROBE, str(outputs[False]), *command], env=environment(False),
                           capture_output=True, check=True)
            subprocess.run([sys.executable, "-c", PROBE, str(outputs[True]), *command], env=environment(True),
                           capture_output=True, check=True)
        else:
            best = {False: float("inf"), True: float("inf")}
            for _round in range(args.repeat):
                for pure in (False, True):
                    best[pure] = min(best[pure], cpu_seconds(command, outputs[pure], pure))
        same = outputs[False].read_bytes() == outputs[True].read_bytes()
        figure = (lambda value: f"{value:,.0f}") if args.instructions else (lambda value: f"{value:.2f}")
        print(f"| {name} | {figure(best[False])} | {figure(best[True])} | {best[True] / best[False]:.2f}x"
              f"{'' if same else ' OUTPUTS DIFFER'} |", flush=True)
        if not same:
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
