"""Seconds of CPU a megabyte of the compiled engine on noise, against the Python stages, one run.

    python3 bench/noise_engine.py [--bytes 1000000] [--repeat 2] [--kind NAME] [--against TREE]

A tap at the wrong baud rate, or a noisy line, records mostly garbage; decoding an hour of it framed the
garbage in Python (dissector/accel/fastsummary.py handed it to the Python stages): 4 to 5 s of CPU a MB of
random bytes. The engine now frames such noise itself (dissector/accel/_noise.h, fastsummary.skip_noise).
For each kind of input, on the same file, this takes the CPU seconds (user + system) of `python3 -m
dissector FILE` with the engine, with VW3_PURE_PYTHON=1 (the Python stages alone), and with --against TREE
(another checkout's engine, built in place there: the tree before a change), best of --repeat interleaved
rounds, checks that every output is the same bytes, and prints seconds a MB and the ratios. Kinds (each
reproducible from its seed):
- random, random-pcap: random bytes, raw and as a pcap of records of 20..60 bytes at 19200 baud's pace;
- near-modbus, near-modbus-pcap: a slave address (1..247) and a common function code (1-6, 15, 16, 23),
  then 0..30 random bytes, again and again: noise that looks like frame starts everywhere;
- captures: the shipped RTU captures (captures/*.bin) one after another, repeated to the size;
- session: the simulator's polling session (dissector/sim/simulate.py, which made captures/*.bin).
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

from dissector.sim.simulate import generate_session  # noqa: E402

CODES = (1, 2, 3, 4, 5, 6, 15, 16, 23)
RTU_CAPTURES = ("atv71_commissioning.bin", "noisy_bus.bin", "p38_protection.bin", "sel749m_polling.bin")


def random_bytes(size: int) -> bytes:
    return random.Random(1).randbytes(size)


def near_modbus(size: int) -> bytes:
    rng = random.Random(2)
    out = bytearray()
    while len(out) < size:
        out += bytes([rng.randint(1, 247), rng.choice(CODES)]) + rng.randbytes(rng.randint(0, 30))
    return bytes(out[:size])


def captures(size: int) -> bytes:
    one = b"".join((ROOT / "captures" / name).read_bytes() for name in RTU_CAPTURES)
    return one * (size // len(one) + 1)


def session(size: int) -> bytes:
    out = bytearray()
    transactions = max(100, size // 30)
    for data, _time in generate_session(transactions, seed=1):
        out += data
        if len(out) >= size:
            break
    return bytes(out)


def as_pcap(data: bytes, seed: int = 3, baud: int = 19200) -> bytes:
    """Records of 20..60 bytes, each stamped where the one before it ends at `baud` (11 bits a
    character): a tap's reads of a line that never goes quiet."""
    rng = random.Random(seed)
    out = bytearray(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147))
    microseconds = 1_700_000_000 * 10**6
    start = 0
    while start < len(data):
        record = data[start : start + rng.randint(20, 60)]
        out += struct.pack("<IIII", microseconds // 10**6, microseconds % 10**6, len(record), len(record)) + record
        microseconds += len(record) * 11 * 10**6 // baud
        start += len(record)
    return bytes(out)


KINDS = {
    "random": (random_bytes, False),
    "random-pcap": (random_bytes, True),
    "near-modbus": (near_modbus, False),
    "near-modbus-pcap": (near_modbus, True),
    "captures": (captures, False),
    "session": (session, False),
}

# Runs a command and prints the CPU seconds (user + system) of it and its children.
PROBE = """
import os, resource, subprocess, sys
with open(sys.argv[1], "wb") as sink:
    result = subprocess.run(sys.argv[2:], stdout=sink, stderr=subprocess.DEVNULL)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(result.returncode, usage.ru_utime + usage.ru_stime)
"""


def cpu_seconds(path: Path, output: Path, tree: Path, pure: bool) -> float:
    env = dict(os.environ, PYTHONPATH=str(tree))
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    command = [sys.executable, "-m", "dissector", str(path)]
    probe = subprocess.run([sys.executable, "-c", PROBE, str(output), *command], env=env, cwd=tree,
                           capture_output=True, text=True, check=True)
    code, seconds = probe.stdout.split()
    if code not in ("0", "1"):  # (1: a warning, e.g. no valid frame in the input)
        sys.exit(f"{' '.join(command)} in {tree} exited {code}")
    return float(seconds)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bytes", type=int, default=1_000_000, help="bytes of each stream (a pcap's payload)")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--kind", action="append", choices=list(KINDS), help="only these kinds")
    parser.add_argument("--against", type=Path, help="another checkout, its engine built in place")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for tree in (ROOT, args.against):
        if tree is not None:
            subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree / "dissector")], check=True)
    sides = {"engine": (ROOT, False), "pure": (ROOT, True)}
    if args.against is not None:
        sides["against"] = (args.against.resolve(), False)
    megabytes = args.bytes / 1e6
    print(f"CPU seconds a MB ({args.bytes:,} bytes a stream), best of {args.repeat}")
    against = " | --against engine | engine vs --against" if args.against is not None else ""
    print(f"| kind | engine | VW3_PURE_PYTHON=1 | engine vs pure{against} |")
    print("|---|---:|---:|---:|" + ("---:|---:|" if args.against is not None else ""))
    for name in args.kind or list(KINDS):
        make, pcap = KINDS[name]
        data = make(args.bytes)
        path = args.out / f"noise-engine-{name}.{'pcap' if pcap else 'bin'}"
        path.write_bytes(as_pcap(data) if pcap else data)
        outputs = {side: args.out / f"noise-engine-{name}-{side}.txt" for side in sides}
        best = {side: float("inf") for side in sides}
        for _round in range(args.repeat):
            for side, (tree, pure) in sides.items():
                best[side] = min(best[side], cpu_seconds(path, outputs[side], tree, pure))
        same = len({outputs[side].read_bytes() for side in sides}) == 1
        row = f"| {name} | {best['engine'] / megabytes:.2f} | {best['pure'] / megabytes:.2f} | {best['pure'] / best['engine']:.2f}x"
        if args.against is not None:
            row += f" | {best['against'] / megabytes:.2f} | {best['against'] / best['engine']:.2f}x"
        print(row + ("" if same else " | OUTPUTS DIFFER") + " |", flush=True)
        if not same:
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
